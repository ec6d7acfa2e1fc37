// The rules of a concurrent stage that span its two programs and so no
// single driver's schema can state: regions that do not overlap, a cell
// edge below the DPD cutoff (seed §2.4), a body on the grid, a pair
// interface with a pair style. The coupler attaches this to the
// `concurrent` kind it learns from dpd_driver --describe, so that a bad
// stage is refused before any rank starts.
#pragma once

#include "pbms/config/stage_kind_spec.hpp"

namespace pbms::coupling {

void check_concurrent_stage(const config::StageCheck& c);

}  // namespace pbms::coupling
