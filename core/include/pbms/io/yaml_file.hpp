// YAML files that a crash must never leave half-written: written to a
// temporary beside the target and renamed over it (atomic on POSIX).
#pragma once

#include <filesystem>
#include <string>

#include <yaml-cpp/yaml.h>

namespace pbms {

// A node as YAML text with every double to 17 digits, so that numbers sent
// to a driver or written to a potential file read back bit for bit.
std::string yaml_text(const YAML::Node& node);

void write_yaml_atomic(const std::filesystem::path& path, const YAML::Node& node,
                       const std::string& header_comment = {});

}  // namespace pbms
