// The `necks` probe of sintering bodies (seed §6.4), declared once for
// every stage kind that follows them: the concurrent stage (bodies in a
// gas, on the shared grid) and the DPD-only stages (dpd_run,
// dpd_equilibrate), so that a pair run DPD-only and in the gas is measured
// by the same keys, outputs and rule (analysis/neck_width.hpp). md_bodies
// declares the same keys for atoms itself: md_driver links only core.
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/stage_kind_spec.hpp"

namespace pbms::coupling {

// A neck between two bodies (groups) that sinter.
struct NeckPair {
  std::string name;
  std::string first, second;
  int second_rod_axis = -1;  // 0..2: `second` is a rod along that axis
};

[[nodiscard]] config::Param necks_param();
[[nodiscard]] config::Param neck_stable_time_param();
[[nodiscard]] std::vector<config::OutputSpec> neck_outputs();
// From a checked stage map's `necks` list.
[[nodiscard]] std::vector<NeckPair> necks_from_yaml(const YAML::Node& necks);

}  // namespace pbms::coupling
