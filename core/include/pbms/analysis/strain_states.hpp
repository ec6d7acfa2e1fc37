// The four strained states behind the cubic elastic constants and the
// arithmetic that turns their stresses into C11, C12, C44 with block
// errors. Pure arithmetic, no engine: dpd_elastic samples all four states in
// one call (dpd_driver/properties/elastic_constants.hpp), while the MD->DPD
// fit's judge (coupler/fit/dpd_judge.cpp) has each state sampled by a
// request of its own, on whichever rank group is free, and combines the
// answers here. One function doing the combination for both is what makes
// the judge's constants equal a dpd_elastic stage's bit for bit, which the
// fit needs for an objective of exactly zero at the parameters that made
// its targets.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "pbms/analysis/block_average.hpp"
#include "pbms/analysis/cubic_moduli.hpp"

namespace pbms::analysis {

// Cauchy stress, GPa, positive in tension: xx, yy, zz, xy, xz, yz.
using CauchyStress = std::array<double, 6>;

// −trace/3, GPa.
inline double pressure_of(const CauchyStress& s) {
  return -(s[0] + s[1] + s[2]) / 3.0;
}

// Blocks of the sampling steps behind every error estimate of the strained
// states (and of the DPD crystal's other properties): few, so that each is
// long against the correlation time (see dpd_driver's ThermalSettings).
inline constexpr int kStateBlocks = 5;

// GPa. Errors are one standard error from block averages (kStateBlocks
// blocks of the sampling steps), 0 when static.
struct ElasticConstants : CubicModuli {
  double c11_error = 0.0, c12_error = 0.0, c44_error = 0.0;
  // Of the derived moduli, block by block, so that the correlation of C11
  // and C12 (the same runs) is accounted for.
  double youngs_100_error = 0.0, bulk_modulus_error = 0.0;
  // Of the unstrained state. Static: exact. At temperature: the mean of the
  // two tetragonal states, high by O(ε²) (~0.001 GPa at the default strain);
  // the cubic crystal of isotherm.hpp reads ~0.002 GPa lower (finite size).
  double pressure = 0.0, pressure_error = 0.0;
};

// The homogeneous strains of the rotated crystal (axes x' = [110],
// y' = [−110], z = [001]): tetragonal diag(1, 1, 1 ± ε) gives C11 and C12,
// (1 ± ε, 1 ∓ ε, 1) the shear ε_xy = ±ε of the cubic axes and so C44.
enum class StrainState { kTetragonalPlus, kTetragonalMinus, kShearPlus, kShearMinus };
inline constexpr std::array<StrainState, 4> kStrainStates{
    StrainState::kTetragonalPlus, StrainState::kTetragonalMinus, StrainState::kShearPlus,
    StrainState::kShearMinus};

// "tetragonal_plus", "tetragonal_minus", "shear_plus", "shear_minus": the
// names dpd_elastic's `strain_state` takes.
std::string strain_state_name(StrainState state);
// Throws pbms::Error for any other name.
StrainState strain_state_from_name(const std::string& name);

// The strain along x', y', z of `state` at magnitude `strain`.
std::array<double, 3> strain_of(StrainState state, double strain);

// The block means of a state's sampled stress: kStateBlocks rows
// (block_means), or one row (the mean) for fewer than kStateBlocks
// samples, the static case.
std::vector<CauchyStress> stress_block_means(const std::vector<CauchyStress>& samples);

// C11, C12, C44 and their errors from the stress block means of the four
// states (indexed as kStrainStates), all sampled at the same lattice
// constant, `strain`, seed and number of steps. Central differences block by
// block: the ± states share their seed and stay synchronised, so most of the
// thermal noise cancels in each block's difference, and the errors of the
// derived moduli carry the covariance of the constants they combine. The
// pressure is the two tetragonal states' mean. Throws pbms::Error for states
// of different block counts or a non-positive strain.
ElasticConstants elastic_constants_from_states(
    const std::array<std::vector<CauchyStress>, 4>& block_means, double strain);

}  // namespace pbms::analysis
