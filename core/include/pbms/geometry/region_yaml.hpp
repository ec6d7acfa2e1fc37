// Regions in workflow configs: the schema a stage declares for a region
// key, and the Region built from the validated YAML. Shared by every driver
// whose stages place particles (MPM bodies, DPD lattices, groups).
#pragma once

#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include "pbms/config/param.hpp"
#include "pbms/geometry/region.hpp"

namespace pbms::geometry {

// A key `name` holding a block, sphere, cylinder, or a union, intersection
// or difference of those (lengths in Å, unit suffixes accepted).
[[nodiscard]] config::Param region_param(const std::string& name, const std::string& doc);

// The region of a node that passed region_param's schema.
[[nodiscard]] std::unique_ptr<Region> region_from_yaml(const YAML::Node& node);

}  // namespace pbms::geometry
