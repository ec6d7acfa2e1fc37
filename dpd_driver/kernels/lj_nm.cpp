#include "kernels/lj_nm.hpp"

#include "kernels/pair_force_loop.hpp"
#include "kernels/pair_parameter_reader.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

std::vector<config::Param> LjNm::params() {
  using config::Param;
  using units::Dimension;
  return {Param::real("e0", Dimension::kEnergy, "Well depth E0").require().above(0),
          Param::real("r0", Dimension::kLength, "Equilibrium distance r0").require().above(0),
          Param::real("n", Dimension::kNone, "Repulsive exponent").require().above(0),
          Param::real("m", Dimension::kNone, "Attractive exponent").require().above(0),
          pair_cutoff_param(),
          pair_shift_param()};
}

std::unique_ptr<PairStyle> LjNm::create(const PairStyleParameters& params) {
  PairParameterReader read(kStyle, params);
  const double e0 = read.required_positive("e0");
  const double r0 = read.required_positive("r0");
  const double n = read.required_positive("n");
  const double m = read.required_positive("m");
  const double cutoff = read.required_positive("cutoff");
  const bool shift = read.optional_flag("shift", false);
  read.reject_unknown();
  if (!(n > m)) read.fail("n", "must be greater than m");
  return std::make_unique<LjNm>(e0, r0, n, m, cutoff, shift);
}

LjNm::LjNm(double e0, double r0, double n, double m, double cutoff, bool shift)
    : kernel_{e0, r0 * r0, n, m, cutoff * cutoff, 0.0}, cutoff_(cutoff) {
  if (!(n > m && m > 0.0)) throw Error("pair style lj_nm: needs n > m > 0");
  if (shift) {
    double at_cutoff = 0.0;
    double unused = 0.0;
    kernel_.evaluate(0, 0, cutoff * cutoff, at_cutoff, unused);
    kernel_.energy_shift = at_cutoff;
  }
}

PairResult LjNm::compute_forces(DpdParticles& particles, const HalfNeighbourList& list, Tally tally,
                                const PairFrictionTerm* friction) {
  return pair_force_loop(kernel_, particles, list, tally, friction);
}

}  // namespace pbms::dpd
