// What the regions of a stage that places particles in a box hold, checked
// from the config alone: bodies inside the box and apart, every group and
// every solver region holding some body, solver regions named once, samples
// taken at least once. The keys are those the DPD stages and the concurrent
// stage publish (box, bodies, groups, regions, initial.from_stage, steps,
// sample_every); the coupler attaches this check to every kind with a box.
#pragma once

#include "pbms/config/stage_kind_spec.hpp"

namespace pbms::config {

void check_body_geometry(const StageCheck& c);

}  // namespace pbms::config
