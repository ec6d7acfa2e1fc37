// The workflow config reference (docs/config-reference.md), generated from
// the same schema that validates configs, so the two cannot drift apart.
#pragma once

#include <string>
#include <vector>

#include "pbms/config/stage_kind_spec.hpp"

namespace pbms::coupler {

std::string config_reference_markdown(const std::vector<config::DriverDescription>& drivers);

}  // namespace pbms::coupler
