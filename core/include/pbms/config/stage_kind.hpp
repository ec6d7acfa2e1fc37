// What a driver declares about one stage kind it can run: its parameters, the
// outputs later stages may reference, and the material kinds it accepts.
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/param.hpp"

namespace pbms::config {

struct OutputSpec {
  enum class Shape { kScalar, kTable };
  std::string name;
  Shape shape = Shape::kScalar;
  std::string unit;  // metal units; "1" for dimensionless
  std::string doc;
};

struct StageKindSpec {
  std::string kind;     // "md_isotherm"
  std::string program;  // "md_driver"
  std::string doc;
  std::vector<Param> params;  // besides the common `name` and `kind`
  std::vector<OutputSpec> outputs;
  std::vector<std::string> material_kinds;  // empty: takes no material
  // A reference result (MD) that depends only on its input: the coupler
  // keeps it in <output>/.cache/ and reuses it instead of running again.
  bool cacheable = false;

  [[nodiscard]] const OutputSpec* output(std::string_view name) const;
};

// What `<driver> --describe` prints and the handshake carries.
struct DriverDescription {
  std::string program;     // "md_driver"
  std::string short_name;  // "md": the key in `launch:` and `--ranks md=2`
  int protocol_version = 0;
  std::vector<StageKindSpec> stage_kinds;
  std::vector<std::pair<std::string, std::string>> software;  // name -> version

  [[nodiscard]] const StageKindSpec* stage_kind(std::string_view kind) const;
};

YAML::Node to_yaml(const StageKindSpec& s);
StageKindSpec stage_kind_from_yaml(const YAML::Node& n);
YAML::Node to_yaml(const DriverDescription& d);
DriverDescription driver_from_yaml(const YAML::Node& n);

}  // namespace pbms::config
