// What `--resume` takes from the run it continues, found in the run
// directory: the resolved config it ran (config.yaml), which stages
// finished (manifest.yaml) and their results (summary.yaml, results.h5),
// and the checkpoints of the stage it was running.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "pbms/results.hpp"

namespace pbms::coupler {

class EarlierRun {
 public:
  // Nothing when `dir` holds no manifest.yaml (a run that never started).
  // Throws pbms::Error when a file is there but cannot be read.
  static std::optional<EarlierRun> read(const std::filesystem::path& dir);

  [[nodiscard]] const YAML::Node& config() const { return config_; }
  [[nodiscard]] const YAML::Node& manifest() const { return manifest_; }
  [[nodiscard]] const YAML::Node& summary() const { return summary_; }
  // Recorded "ok" in the manifest, with its results in the summary.
  [[nodiscard]] bool finished(const std::string& stage) const;
  // A finished stage's results as its driver returned them: the scalars
  // from summary.yaml, the tables from results.h5, files and warnings from
  // the manifest.
  [[nodiscard]] StageResults results_of(const std::string& stage) const;
  // The stage's manifest entry, or a null node.
  [[nodiscard]] YAML::Node stage_entry(const std::string& stage) const;

 private:
  std::filesystem::path dir_;
  YAML::Node config_, manifest_, summary_;
};

// The first place where two resolved configs differ, as "KEY: A in the
// earlier run, B now", or empty when they agree. `launch`, `run.name` and
// `run.output` are left out: a resumed run may take other rank counts, and
// a run directory may be moved.
[[nodiscard]] std::string first_difference(const YAML::Node& then, const YAML::Node& now);

}  // namespace pbms::coupler
