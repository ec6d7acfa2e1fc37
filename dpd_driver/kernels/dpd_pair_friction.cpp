#include "kernels/dpd_pair_friction.hpp"

#include <cmath>

#include "kernels/pair_noise.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

void add_dissipative_random_forces(DpdParticles& particles, const std::vector<Vec3>& velocity,
                                   const HalfNeighbourList& list, const DpdPairFriction& friction,
                                   std::int64_t step, double dt) {
  using units::kBoltzmann;
  using units::kMvv2e;
  // Both prefactors in eV/Å per unit weight: γ (g/mol/ps) · v (Å/ps) is a
  // momentum rate, and σ = sqrt(2 γ k_B T / mvv2e) in the same mass units.
  const double friction_factor = friction.gamma * kMvv2e;
  const double noise_factor =
      std::sqrt(2.0 * friction.gamma * kBoltzmann * friction.temperature * kMvv2e / dt);
  const double cutoff_squared = friction.cutoff * friction.cutoff;
  const double inverse_cutoff = 1.0 / friction.cutoff;

  const std::size_t n = list.particle_count();
  const HalfNeighbourList::Entry* entries = list.entries();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = list.first(i); k < list.first(i + 1); ++k) {
      const std::size_t j = HalfNeighbourList::neighbour(entries[k]);
      const Vec3 d = list.separation(particles.x.data(), i, entries[k]);
      const double dx = d[0], dy = d[1], dz = d[2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= cutoff_squared) continue;
      const double r = std::sqrt(r2);
      const double ex = dx / r, ey = dy / r, ez = dz / r;
      const double w_r = 1.0 - r * inverse_cutoff;
      const double approach = ex * (velocity[i][0] - velocity[j][0]) +
                              ey * (velocity[i][1] - velocity[j][1]) +
                              ez * (velocity[i][2] - velocity[j][2]);
      const double theta =
          pair_gaussian_pair_noise(friction.seed, particles.id[i], particles.id[j], step);
      const double magnitude = -friction_factor * w_r * w_r * approach + noise_factor * w_r * theta;
      particles.f[i][0] += magnitude * ex;
      particles.f[i][1] += magnitude * ey;
      particles.f[i][2] += magnitude * ez;
      particles.f[j][0] -= magnitude * ex;
      particles.f[j][1] -= magnitude * ey;
      particles.f[j][2] -= magnitude * ez;
    }
  }
}

}  // namespace pbms::dpd
