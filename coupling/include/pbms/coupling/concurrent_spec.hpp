// The schema of a concurrent DPD/MPM stage (its keys, defaults and
// outputs), declared once beside its typed parameters (ConcurrentParams)
// and its cross-program check. dpd_driver publishes it as its `concurrent`
// stage kind; mpm_driver's part reads the same parameters.
#pragma once

#include <vector>

#include "pbms/config/stage_kind_spec.hpp"

namespace pbms::coupling {

// The `concurrent` stage kind: `body_params` are the keys that build the
// body (bodies or an earlier state, groups, motion: the DPD stages' own),
// without their `grid`, which the stage declares for both programs.
[[nodiscard]] config::StageKindSpec concurrent_spec(std::vector<config::Param> body_params);

}  // namespace pbms::coupling
