// The pair-dependent factors of the DPD friction force (dpd_pair_friction.hpp)
// for a batch of pairs, folded into the conservative force over r, so that
// the force loop only has to form
//   (F^C_ij + F^D_ij + F^R_ij) / r = total_over_r − drag · (r_ij · v_ij)
// with
//   total_over_r = F^C/r + σ' θ_ij w/r,   drag = γ' (w/r)²,   w = max(0, 1 − r/r_c),
// σ' = noise_factor and γ' = friction_factor of the PairFrictionTerm.
//
// This is the thermostat's whole cost beyond the conservative loop but for
// the velocities, so it is one pass over the batch: with AVX-512 the noise
// counters are formed, Philox runs (philox_avx512.hpp) and uniform θ is
// made in registers, 8 pairs to a register, next to the weights; 1/r is
// vrsqrt14pd refined by two Newton steps (2^-14 → 2^-28 → 2^-53 relative)
// instead of a square root and a division, which cost as much as the rest of
// the arithmetic. Gaussian θ comes from pair_noise_batch. θ has the same
// bits on every path (pair_noise.hpp), and every pair of a run takes the same
// path, wherever in a batch it lies.
#pragma once

#include <cstdint>

#include "kernels/dpd_pair_friction.hpp"
#include "kernels/philox_lanes.hpp"

namespace pbms::dpd {

// id_pair[m]: the pair's two 32-bit global ids, the lower in the low half
// (as HalfNeighbourList::pair_ids keeps them); r2[m] > 0: its squared separation (Å²); force_over_r[m]: its
// conservative force over r (eV/Å²). Any count ≥ 0.
void pair_friction_coefficients(const PairFrictionTerm& term, const std::uint64_t* id_pair,
                                const double* r2, const double* force_over_r, int count,
                                double* total_over_r, double* drag);
// The same on a given path (kAvx2 takes the portable one), for tests.
void pair_friction_coefficients(SimdPath path, const PairFrictionTerm& term,
                                const std::uint64_t* id_pair, const double* r2,
                                const double* force_over_r, int count, double* total_over_r,
                                double* drag);

}  // namespace pbms::dpd
