// The concurrent DPD/MPM stage (seed §5.3; METHOD.md §3): one body on one
// grid, its regions advanced by dpd_driver (DPD particles through the grid)
// or mpm_driver (elastic material points on the same lattice sites), the
// two exchanging interface data rank to rank every step. dpd_driver builds
// the body, hands mpm_driver its points once, and both then step together
// under one CouplingScheme; the coupler starts mpm_driver's part with the
// same parameters and collects both results.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::dpd {

class ConcurrentStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::dpd
