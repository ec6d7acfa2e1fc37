// Initial velocities drawn from the Maxwell–Boltzmann distribution. Each
// particle's three components come from a Philox draw keyed by (seed, its
// global id), so a particle gets the same velocity whatever rank holds it
// and in whatever order particles are stored.
#pragma once

#include <cstdint>

#include "kernels/dpd_particles.hpp"

namespace pbms::dpd {

// "MBvelo" in ASCII: keeps these draws apart from the pair noise of the same seed.
inline constexpr std::uint64_t kMaxwellBoltzmannStream = 0x00004d4276656c6fULL;

// Sets v_i ~ N(0, k_B T / m_i) per component, then removes the centre-of-mass
// velocity and rescales so that the kinetic temperature (3N − 3 degrees of
// freedom) is exactly temperature (K). Serial: the two corrections are sums
// over all particles.
void assign_maxwell_boltzmann_velocities(DpdParticles& particles, double temperature,
                                         std::uint64_t seed);

}  // namespace pbms::dpd
