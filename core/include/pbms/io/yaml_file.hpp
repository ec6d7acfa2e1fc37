// YAML files that a crash must never leave half-written: written to a
// temporary beside the target and renamed over it (atomic on POSIX).
#pragma once

#include <filesystem>

#include <yaml-cpp/yaml.h>

namespace pbms {

void write_yaml_atomic(const std::filesystem::path& path, const YAML::Node& node,
                       const std::string& header_comment = {});

}  // namespace pbms
