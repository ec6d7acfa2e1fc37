// What a driver declares about one stage kind it can run: its parameters, the
// outputs later stages may reference, and the material kinds it accepts.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/param.hpp"

namespace pbms::config {

class Validator;
struct DriverDescription;

struct OutputSpec {
  // kMap: a YAML map (a fitted potential), for keys of map kind.
  enum class Shape { kScalar, kTable, kMap };
  std::string name;
  Shape shape = Shape::kScalar;
  std::string unit;  // metal units; "1" for dimensionless
  std::string doc;
};

// "scalar", "table" or "map".
const char* shape_name(OutputSpec::Shape shape);

// What a stage kind's own check sees, after the schema and the references
// between stages have been checked and potential files read.
struct StageCheck {
  Validator& validator;
  const YAML::Node& raw;        // the stage as written (marks for errors)
  const YAML::Node& resolved;   // defaults filled, metal units
  const std::string& path;      // "stages[3]"
  const YAML::Node& materials;  // resolved `materials:`, potential files read
  const std::vector<DriverDescription>& drivers;
  const YAML::Node& workflow;  // the whole resolved workflow (other stages, launch)
};

// For checks that look at other stages: the stage of that name among
// workflow["stages"] (a null node when there is none), and the stage and
// output a `{from: stage.output}` node names (both empty for a literal).
[[nodiscard]] YAML::Node stage_named(const YAML::Node& workflow, const std::string& name);
[[nodiscard]] std::pair<std::string, std::string> reference_source(const YAML::Node& node);

struct StageKindSpec {
  std::string kind;     // "md_isotherm"
  std::string program;  // "md_driver", or "coupler" for a kind the coupler runs itself
  std::string doc;
  std::vector<Param> params;  // besides the common `name` and `kind`
  std::vector<OutputSpec> outputs;
  std::vector<std::string> material_kinds;  // empty: takes no material
  // A reference result (MD) that depends only on its input: the coupler
  // keeps it in <output>/.cache/ and reuses it instead of running again.
  bool cacheable = false;
  // Writes checkpoints when the workflow has a `checkpoint:` block, and
  // goes on from one on --resume (docs/checkpoints.md).
  bool checkpoints = false;
  // A coupler-side kind: the drivers it sends requests to.
  std::vector<std::string> uses;
  // A kind run by several drivers together (a concurrent DPD/MPM stage):
  // the coupler sends the same parameters to each partner program as its
  // `kind`, at the same time as to `program`, and collects every answer.
  struct Partner {
    std::string program;
    std::string kind;
  };
  std::vector<Partner> partners;
  // Only ever a partner's part of another kind; a workflow may not name it.
  bool internal = false;
  // Checks the schema cannot express (a fit's free parameters against the
  // material's pair style); reports through the validator. Declared beside
  // the kind's code, in-process only: never part of --describe.
  std::function<void(const StageCheck&)> check;

  [[nodiscard]] const OutputSpec* output(std::string_view name) const;
};

// A kind of entry under `materials:` that a driver's stages take (eam_alloy,
// linear_elastic, dpd_mesoparticle): declared beside the code that reads
// it, and published through --describe, so that the coupler validates a
// material without knowing any driver's styles.
struct MaterialKindSpec {
  std::string kind;
  std::string doc;
  std::vector<Param> params;  // besides `kind`
};

// What `<driver> --describe` prints and the handshake carries.
inline constexpr const char* kCouplerProgram = "coupler";

struct DriverDescription {
  std::string program;     // "md_driver"
  std::string short_name;  // "md": the key in `launch:` and `--ranks md=2`
  int protocol_version = 0;
  std::vector<StageKindSpec> stage_kinds;
  std::vector<MaterialKindSpec> material_kinds;
  std::vector<std::pair<std::string, std::string>> software;  // name -> version

  [[nodiscard]] const StageKindSpec* stage_kind(std::string_view kind) const;
};

// The material kind some driver declares, or null.
[[nodiscard]] const MaterialKindSpec* find_material_kind(
    const std::vector<DriverDescription>& drivers, std::string_view kind);
// Field `name` of a material kind (e.g. dpd_mesoparticle's `potential`),
// or null.
[[nodiscard]] const Param* material_field(const std::vector<DriverDescription>& drivers,
                                          std::string_view kind, std::string_view name);

YAML::Node to_yaml(const StageKindSpec& s);
StageKindSpec stage_kind_from_yaml(const YAML::Node& n);
YAML::Node to_yaml(const DriverDescription& d);
DriverDescription driver_from_yaml(const YAML::Node& n);

}  // namespace pbms::config
