// The stochastic half of the Shardlow S1 splitting (Shardlow 2003, SIAM J.
// Sci. Comput. 24, 1267) in the form of Lísal, Brennan & Avalos (2011),
// J. Chem. Phys. 135, 204105: the dissipative and random forces of each
// pair in turn act on that pair's velocities alone, over one time step,
// before the conservative velocity-Verlet step. Each pair update is two half
// steps with the same θ_ij, the second implicit in the new relative velocity
// and solved in closed form, so the update is unconditionally stable in γ and
// conserves the pair's momentum exactly.
//
// Isothermal DPD takes σ² = 2 γ k_B T from the bath. DPDE (Avalos & Mackie
// 1997, Español 1997) takes σ_ij² = 2 γ k_B θ_ij from the pair's
// mesoparticle temperatures, θ_i = u_i / C_v and 1/θ_ij = (1/θ_i + 1/θ_j)/2,
// and moves the kinetic energy each pair update changes into the two
// internal energies, half each, so K + U + Σ u is conserved to round-off by
// the sweep (U does not change in it: positions are fixed).
#pragma once

#include <cstdint>
#include <span>

#include "kernels/dpd_pair_friction.hpp"
#include "kernels/dpd_particles.hpp"
#include "kernels/shardlow_pair_order.hpp"

namespace pbms::dpd {

// Updates the given pairs that are closer than friction.cutoff, in order
// (ShardlowPairOrder gives them, a colour at a time), with the bath
// temperature friction.temperature. step keys θ_ij; dt in ps.
void shardlow_sweep(DpdParticles& particles, std::span<const ShardlowPair> pairs,
                    const DpdPairFriction& friction, std::int64_t step, double dt);

// The DPDE sweep: friction.temperature is ignored, heat_capacity (C_v, eV/K,
// the same for every mesoparticle) turns particles.internal_energy into
// temperatures. Throws pbms::Error when a pair's internal energies are not
// both positive, where θ_ij and σ_ij are undefined (dt too large for C_v).
void shardlow_sweep_energy_conserving(DpdParticles& particles, std::span<const ShardlowPair> pairs,
                                      const DpdPairFriction& friction, double heat_capacity,
                                      std::int64_t step, double dt);

}  // namespace pbms::dpd
