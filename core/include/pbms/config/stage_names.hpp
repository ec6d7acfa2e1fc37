// A stage's own names: bodies and groups name sets of particles or points
// (Param::with_stage_names), and motions, grips, probes and the tension's
// specimen name one of them (Param::names_entry_of). Both are checked from
// the config alone, before any rank starts: a name given twice, or a key
// naming no body or group of its stage, would otherwise end the job inside
// a driver.
#pragma once

#include <vector>

#include "pbms/config/validator.hpp"

namespace pbms::config {

// Reports through `v` every repeated name and every unresolved name among
// the stage-name references the validator collected.
void check_stage_names(const std::vector<Reference>& refs, Validator& v);

}  // namespace pbms::config
