// Reads a YAML file that a user wrote (a workflow, a DPD potential file) and
// refuses, with file:line:col, what would crash, hang or silently misread a
// YAML parser: files over 1 MiB, over-long lines, bytes that are not text,
// syntax errors, undefined or recursive aliases, aliases that expand to a
// huge document, and a second document in the file.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "pbms/config/validator.hpp"

namespace pbms::config {

// A workflow is a short text; anything larger is the wrong file.
inline constexpr std::size_t kMaxYamlBytes = 1024 * 1024;
inline constexpr std::size_t kMaxYamlLineBytes = 64 * 1024;
// Values the document may hold once aliases are expanded.
inline constexpr std::size_t kMaxYamlValues = 1000000;

// Loads `path` (already known to exist) into a node; on any problem reports
// it through `v` (whose file is `path`) and returns nothing. `what` names the
// file for messages: "a workflow", "a potential file".
std::optional<YAML::Node> load_yaml_source(const std::string& path, Validator& v,
                                           const std::string& what);

// The same for text already read (unit tests).
std::optional<YAML::Node> parse_yaml_source(const std::string& text, Validator& v,
                                            const std::string& what);

}  // namespace pbms::config
