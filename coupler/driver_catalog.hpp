// The drivers installed next to the coupler and what they declare, learned
// by running `<driver> --describe` (no MPI involved).
#pragma once

#include <filesystem>
#include <vector>

#include "pbms/config/stage_kind_spec.hpp"

namespace pbms::coupler {

// The drivers' descriptions, then the coupler's own (its coupler-side kinds).
std::vector<config::DriverDescription> discover_drivers(const std::filesystem::path& dir);

}  // namespace pbms::coupler
