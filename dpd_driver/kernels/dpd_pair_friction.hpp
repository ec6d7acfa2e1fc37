// The dissipative and random pair forces of isothermal DPD in the form of
// Groot & Warren (1997), J. Chem. Phys. 107, 4423:
//   F^D_ij = −γ w_D(r) (e_ij · v_ij) e_ij,
//   F^R_ij = σ w_R(r) θ_ij Δt^{−1/2} e_ij,
//   w_R = 1 − r/r_c,  w_D = w_R²,  σ² = 2 γ k_B T,
// which by fluctuation–dissipation (Español & Warren 1995) leave the
// canonical distribution at T invariant. θ_ij has zero mean and unit
// variance (Gaussian or uniform, pair_noise.hpp) and is keyed by (seed, the
// pair's global ids, step), so both members of a pair, and every rank that
// holds it, draw the same number.
//
// γ is a friction coefficient in g/mol/ps (the seed's 0.2 amu/ps), not
// LAMMPS pair dpd's force/velocity: γ v is a momentum rate, turned into eV/Å
// by mvv2e. The DPD cutoff r_c is its own parameter, independent of the
// conservative style's.
#pragma once

#include <cstdint>
#include <vector>

#include "kernels/dpd_particles.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/pair_noise.hpp"
#include "kernels/pair_style.hpp"

namespace pbms::dpd {

struct DpdPairFriction {
  double gamma = 0.0;        // g/mol/ps
  double cutoff = 0.0;       // Å, range of w_R and w_D
  double temperature = 0.0;  // K, the bath of σ² = 2 γ k_B T
  std::uint64_t seed = 0;    // keys θ_ij
  PairNoiseDistribution noise = PairNoiseDistribution::kUniform;
};

// One step's friction, as the pair loop evaluates it: the prefactors in
// eV/Å per unit weight, the noise key and the velocities F^D sees.
struct PairFrictionTerm {
  PairFrictionTerm(const DpdPairFriction& friction, const std::vector<Vec3>& velocity,
                   std::int64_t step, double dt);
  const Vec3* velocity;
  PairNoise noise;
  std::int64_t step;
  double cutoff;
  double inverse_cutoff;
  double friction_factor;  // γ mvv2e
  double noise_factor;     // σ / √Δt = √(2 γ k_B T mvv2e / Δt)
};

// Adds F^D + F^R of every listed pair closer than friction.cutoff to
// particles.f, the dissipative part from the given velocities (one per
// particle: the integrator decides which velocity estimate F^D sees). step
// keys the noise; dt (ps) scales it. The list must reach friction.cutoff.
void add_dissipative_random_forces(DpdParticles& particles, const std::vector<Vec3>& velocity,
                                   const HalfNeighbourList& list, const DpdPairFriction& friction,
                                   std::int64_t step, double dt);

// Conservative plus dissipative and random forces, added to particles.f:
// one pass over the list when the DPD cutoff is within the style's, two
// otherwise. Same arguments as above.
PairResult add_conservative_and_friction_forces(PairStyle& pair, DpdParticles& particles,
                                                const std::vector<Vec3>& velocity,
                                                const HalfNeighbourList& list,
                                                const DpdPairFriction& friction, std::int64_t step,
                                                double dt, Tally tally);

}  // namespace pbms::dpd
