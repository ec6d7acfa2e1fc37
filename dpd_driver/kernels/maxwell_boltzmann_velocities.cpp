#include "kernels/maxwell_boltzmann_velocities.hpp"

#include <Random123/philox.h>

#include <cmath>
#include <numbers>

#include "kernels/kinetic_sums.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

namespace {

double open_unit_interval(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

}  // namespace

void assign_maxwell_boltzmann_velocities(DpdParticles& particles, double temperature,
                                         std::uint64_t seed) {
  using Generator = r123::Philox4x64;
  const Generator::key_type key = {{seed, kMaxwellBoltzmannStream}};
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Generator::ctr_type counter = {{static_cast<std::uint64_t>(particles.id[i]), 0, 0, 0}};
    const Generator::ctr_type bits = Generator()(counter, key);
    // Two Box–Muller pairs; three of the four Gaussians are used.
    const double r1 = std::sqrt(-2.0 * std::log(open_unit_interval(bits[0])));
    const double phi1 = 2.0 * std::numbers::pi * open_unit_interval(bits[1]);
    const double r2 = std::sqrt(-2.0 * std::log(open_unit_interval(bits[2])));
    const double phi2 = 2.0 * std::numbers::pi * open_unit_interval(bits[3]);
    const double scale =
        std::sqrt(units::kBoltzmann * temperature / (particles.mass(i) * units::kMvv2e));
    particles.v[i] = {scale * r1 * std::cos(phi1), scale * r1 * std::sin(phi1),
                      scale * r2 * std::cos(phi2)};
  }
  if (particles.size() < 2) return;

  const Vec3 momentum = total_momentum(particles);
  double mass = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) mass += particles.mass(i);
  for (auto& v : particles.v) {
    for (int a = 0; a < 3; ++a) v[a] -= momentum[a] / mass;
  }
  const double current = kinetic_temperature(particles);
  if (current > 0.0) {
    const double factor = std::sqrt(temperature / current);
    for (auto& v : particles.v) {
      for (int a = 0; a < 3; ++a) v[a] *= factor;
    }
  }
}

}  // namespace pbms::dpd
