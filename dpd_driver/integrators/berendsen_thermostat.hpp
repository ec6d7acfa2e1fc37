// The weak-coupling thermostat of Berendsen et al. (1984), J. Chem. Phys.
// 81, 3684, as LAMMPS fix temp/berendsen applies it: after each step all
// velocities are scaled by λ = sqrt(1 + (Δt/τ)(T_0/T − 1)), so that T relaxes
// exponentially to T_0 with time constant τ. It does not sample the canonical
// ensemble (kinetic-energy fluctuations are suppressed), which is why it is
// used for equilibration only, as in the seed (§5.2.1, §6.2.1).
#pragma once

#include <cmath>

#include "kernels/dpd_particles.hpp"
#include "kernels/kinetic_sums.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

// Scales the velocities towards target_temperature (K) over one step of dt
// with coupling time tau (both ps), and returns λ. Throws pbms::Error for a
// non-positive tau or when the particles are at rest (nothing to scale).
inline double berendsen_rescale(DpdParticles& particles, double target_temperature, double dt,
                                double tau) {
  if (!(tau > 0.0)) throw Error("Berendsen thermostat: tau must be > 0 ps");
  const double current = kinetic_temperature(particles);
  if (!(current > 0.0)) {
    throw Error("Berendsen thermostat: the particles are at rest; assign velocities first");
  }
  const double lambda = std::sqrt(1.0 + dt / tau * (target_temperature / current - 1.0));
  for (auto& v : particles.v) {
    for (double& component : v) component *= lambda;
  }
  return lambda;
}

}  // namespace pbms::dpd
