// Checks a YAML tree against a Param schema. Collects every error instead of
// stopping at the first, and produces the resolved tree: defaults filled in,
// quantities converted to metal units.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/param.hpp"
#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/error.hpp"

namespace pbms::config {

// A `{from: stage.output}` found while validating, or a name of a material
// or of a stage; checked by the workflow, which knows the stage order and
// what each stage kind produces.
struct Reference {
  // kStageName: a name declared by an entry of a stage's list (a body or
  // group); kStageEntry: a key that must name one.
  enum class Target { kStageOutput, kMaterial, kStage, kStageName, kStageEntry };
  Target type = Target::kStageOutput;
  std::string key_path;
  std::string target;  // "stage.output", or a material, stage, body or group name
  // kStage: the stage kinds the key takes; kStageName: the declaring list;
  // kStageEntry: the lists whose names it takes.
  std::vector<std::string> kinds;
  // What the key takes: a number, a table (kTable keys) or a map.
  OutputSpec::Shape wants = OutputSpec::Shape::kScalar;
  int line = 0, column = 0;
};

class Validator {
 public:
  explicit Validator(std::string file) : file_(std::move(file)) {}

  // Validates `node` against `schema` at `path`; returns the resolved node.
  YAML::Node check(const Param& schema, const YAML::Node& node, const std::string& path);
  // Validates a map node against an explicit list of fields.
  YAML::Node check_fields(const std::vector<const Param*>& fields, const YAML::Node& node,
                          const std::string& path);

  void error(const YAML::Node& at, const std::string& path, const std::string& message);
  void error_at(const YAML::Mark& mark, const std::string& path, const std::string& message);
  // A legal value that is probably a mistake: reported, stops nothing.
  void warn(const YAML::Node& at, const std::string& path, const std::string& message);

  [[nodiscard]] const std::vector<ConfigError>& errors() const { return errors_; }
  [[nodiscard]] const std::vector<ConfigError>& warnings() const { return warnings_; }
  [[nodiscard]] const std::vector<Reference>& references() const { return references_; }
  [[nodiscard]] const std::string& file() const { return file_; }

 private:
  // `{from: ...}` in place of a value: recorded for the workflow to resolve.
  YAML::Node record_stage_output_reference(const Param& p, const YAML::Node& node,
                                           const std::string& path);
  YAML::Node check_map(const Param& p, const YAML::Node& node, const std::string& path);
  YAML::Node check_map_of(const Param& p, const YAML::Node& node, const std::string& path);
  YAML::Node check_list(const Param& p, const YAML::Node& node, const std::string& path);
  // A scalar, and the material or stage it names, if its key names one.
  YAML::Node check_leaf(const Param& p, const YAML::Node& node, const std::string& path);
  void check_exclusions(const std::vector<const Param*>& fields, const YAML::Node& node,
                        const std::string& path);
  void check_bounds(const Param& p, const YAML::Node& node, const YAML::Node& out,
                    const std::string& path);
  // Records the name an entry of a declaring list gives (Param::declares_names).
  void declare_name(const std::string& list, const YAML::Node& entry, const std::string& path);
  static Reference reference(Reference::Target type, const YAML::Node& node,
                             const std::string& path, std::vector<std::string> kinds = {});
  YAML::Node check_scalar(const Param& p, const YAML::Node& node, const std::string& path);
  YAML::Node check_integer(const Param& p, const YAML::Node& node, const std::string& path);
  YAML::Node check_real(const Param& p, const YAML::Node& node, const std::string& path);
  YAML::Node check_file(const YAML::Node& node, const std::string& path);
  void check_unique_keys(const YAML::Node& node, const std::string& path);
  // Keys given although their only_with sibling resolved to another value.
  void check_only_with(const std::vector<const Param*>& fields, const YAML::Node& node,
                       const YAML::Node& resolved, const std::string& path);
  bool check_range(const Param& p, double v, const YAML::Node& node, const std::string& path);

  std::string file_;
  std::vector<ConfigError> errors_;
  std::vector<ConfigError> warnings_;
  std::vector<Reference> references_;
};

std::string join_path(const std::string& parent, const std::string& key);
// A user's value inside a message: a long one (a line of megabytes) is cut
// to `n` characters and "...".
std::string clipped(const std::string& s, size_t n = 60);
// Why `file` cannot be read as a regular file ("does not exist", "cannot
// exist: '/etc/hostname' is a file, not a directory"), or empty if it can.
std::string file_problem(const std::filesystem::path& file);
// Why the directory `dir` cannot be created or written, or empty.
std::string directory_problem(const std::filesystem::path& dir);
// "did you mean 'x'?" for near misses (edit distance <= 2), else empty.
std::string suggest(const std::string& key, const std::vector<std::string>& candidates);

}  // namespace pbms::config
