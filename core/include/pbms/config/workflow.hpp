// The workflow a user writes: run identity, launch layout, materials and an
// ordered list of stages. Loading checks everything that can be checked
// before any process starts and reports all problems at once.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/param.hpp"
#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/error.hpp"

namespace pbms::config {

struct StageConfig {
  std::string name;
  std::string kind;
  std::string program;               // driver that runs it, or "coupler" for a coupler-side kind
  std::vector<std::string> drivers;  // drivers it sends requests to
  YAML::Node params;                 // resolved: defaults filled, quantities in metal units
  int line = 0;
};

struct Workflow {
  std::string source_file;
  std::string run_name;
  int run_name_line = 0, run_name_column = 0;  // where run.name is written
  std::string output_dir;
  uint64_t seed = 0;
  std::map<std::string, int> ranks;  // program -> rank count, for drivers in use
  YAML::Node materials;
  std::vector<StageConfig> stages;
  YAML::Node resolved;  // the whole resolved config, written into each run dir
  // Legal but suspicious values, each formatted "file:line:col: warning: ...".
  std::vector<std::string> warnings;

  [[nodiscard]] std::filesystem::path run_dir() const;
  // Drivers the stages need, in order of first use.
  [[nodiscard]] std::vector<std::string> programs() const;
};

struct LoadResult {
  std::optional<Workflow> workflow;
  std::vector<ConfigError> errors;
  std::vector<ConfigError> warnings;  // reported whether or not there are errors
};

// `drivers` are the stage kinds the installed drivers declare.
LoadResult load_workflow(const std::string& path, const std::vector<DriverDescription>& drivers);

// The schema of the workflow file for the given drivers (docs, validation).
Param workflow_schema(const std::vector<DriverDescription>& drivers);
// `materials:`, each entry of a kind some driver declares.
Param materials_schema(const std::vector<DriverDescription>& drivers);

// Applies `--ranks md=2` style overrides. Returns an error message, or empty.
std::string apply_rank_override(Workflow& wf, const std::vector<DriverDescription>& drivers,
                                const std::string& spec);

}  // namespace pbms::config
