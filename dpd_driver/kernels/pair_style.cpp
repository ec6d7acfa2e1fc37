#include "kernels/pair_style.hpp"

#include <string>

#include "kernels/dpd_pair_friction.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

PairResult PairStyle::compute(DpdParticles& particles, const HalfNeighbourList& list, Tally tally,
                              const PairFrictionTerm* friction) {
  if (friction != nullptr && friction->cutoff > cutoff()) {
    throw Error("pair style " + std::string(name()) + ": the DPD cutoff (" +
                std::to_string(friction->cutoff) + " Å) exceeds the style's (" +
                std::to_string(cutoff()) + " Å), so one pass cannot hold both");
  }
  return compute_forces(particles, list, tally, friction);
}

config::Param pair_cutoff_param() {
  return config::Param::real("cutoff", units::Dimension::kLength,
                             "Beyond this distance the style contributes nothing")
      .require()
      .above(0);
}

config::Param pair_shift_param() {
  return config::Param::boolean("shift",
                                "Shift energies to zero at the cutoff (LAMMPS pair_modify shift "
                                "yes)")
      .def(false);
}

}  // namespace pbms::dpd
