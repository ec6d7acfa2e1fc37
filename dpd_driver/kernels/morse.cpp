#include "kernels/morse.hpp"

#include <algorithm>
#include <string>

#include "kernels/pair_force_loop.hpp"
#include "kernels/pair_parameter_reader.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

std::vector<config::Param> Morse::params() {
  using config::Param;
  using units::Dimension;
  return {Param::real("d0", Dimension::kEnergy, "Well depth D0").require().above(0),
          Param::real("alpha", Dimension::kNone, "Width alpha, 1/Å").require().above(0),
          Param::real("r0", Dimension::kLength, "Equilibrium distance r0").require().above(0),
          pair_cutoff_param(), pair_shift_param()};
}

std::unique_ptr<PairStyle> Morse::create(const PairStyleParameters& params) {
  PairParameterReader read(kStyle, params);
  const double d0 = read.required_positive("d0");
  const double alpha = read.required_positive("alpha");
  const double r0 = read.required_positive("r0");
  const double cutoff = read.required_positive("cutoff");
  const bool shift = read.optional_flag("shift", false);
  read.reject_unknown();
  return std::make_unique<Morse>(d0, alpha, r0, cutoff, shift);
}

Morse::Morse(double d0, double alpha, double r0, double cutoff, bool shift)
    : kernel_{d0, alpha, r0, cutoff * cutoff, 0.0}, cutoff_(cutoff) {
  // The exponent −α(r − r0) spans [−α(rc − r0), α r0] for 0 < r < rc.
  if (alpha * std::max(r0, cutoff - r0) > kBranchFreeExpLimit) {
    throw Error("pair style morse: alpha · max(r0, cutoff − r0) must be at most " +
                std::to_string(kBranchFreeExpLimit));
  }
  if (shift) {
    double at_cutoff = 0.0;
    double unused = 0.0;
    kernel_.evaluate(0, 0, cutoff * cutoff, at_cutoff, unused);
    kernel_.energy_shift = at_cutoff;
  }
}

PairResult Morse::compute_forces(DpdParticles& particles, const HalfNeighbourList& list,
                                 Tally tally, const PairFrictionTerm* friction) {
  return pair_force_loop(kernel_, particles, list, tally, friction);
}

}  // namespace pbms::dpd
