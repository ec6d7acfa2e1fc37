// Sums over the particles' velocities that thermodynamic output and the
// thermostats need: kinetic energy, kinetic temperature, momentum.
#pragma once

#include <cmath>
#include <cstddef>

#include "kernels/dpd_particles.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

// Σ ½ m v², eV.
inline double kinetic_energy(const DpdParticles& particles) {
  double twice = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3& v = particles.v[i];
    twice += particles.mass(i) * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return 0.5 * twice * units::kMvv2e;
}

// 2 K / (N_dof k_B), K. Every scheme here conserves total momentum, so the
// centre of mass holds three degrees of freedom that carry no heat.
inline double kinetic_temperature(const DpdParticles& particles) {
  const double dof = 3.0 * static_cast<double>(particles.size()) - 3.0;
  return dof > 0.0 ? 2.0 * kinetic_energy(particles) / (dof * units::kBoltzmann) : 0.0;
}

// Σ m v, g/mol·Å/ps.
inline Vec3 total_momentum(const DpdParticles& particles) {
  Vec3 p{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < particles.size(); ++i) {
    for (int a = 0; a < 3; ++a) p[a] += particles.mass(i) * particles.v[i][a];
  }
  return p;
}

// Σ m |v|, g/mol·Å/ps: the scale against which a total momentum of
// thermal motion is small or not (|Σ m v| ≤ Σ m |v|, with near equality
// only for a collective drift).
inline double momentum_magnitude_sum(const DpdParticles& particles) {
  double sum = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3& v = particles.v[i];
    sum += particles.mass(i) * std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return sum;
}

// Σ u_i, eV: the DPDE internal energy.
inline double internal_energy_sum(const DpdParticles& particles) {
  double sum = 0.0;
  for (const double u : particles.internal_energy) sum += u;
  return sum;
}

}  // namespace pbms::dpd
