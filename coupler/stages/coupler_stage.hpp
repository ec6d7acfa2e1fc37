// Stage kinds the coupler runs itself (a fit, a parameter study). They reach
// the drivers only through requests to the scheduler, as the workflow does,
// and report results like any stage; the coupler stays off the data path.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/workflow.hpp"
#include "pbms/results.hpp"
#include "scheduler.hpp"

namespace pbms::coupler {

class CouplerStageContext {
 public:
  CouplerStageContext(Scheduler& scheduler, const config::StageConfig& stage,
                      const YAML::Node& materials,
                      const std::vector<config::DriverDescription>& drivers,
                      std::filesystem::path run_dir, uint64_t seed, bool resume)
      : scheduler_(scheduler),
        stage_(stage),
        materials_(materials),
        drivers_(drivers),
        run_dir_(std::move(run_dir)),
        seed_(seed),
        resume_(resume) {}

  [[nodiscard]] Scheduler& scheduler() { return scheduler_; }
  [[nodiscard]] const config::StageConfig& stage() const { return stage_; }
  // The stage's parameters, references to earlier results replaced.
  [[nodiscard]] const YAML::Node& params() const { return stage_.params; }
  [[nodiscard]] const YAML::Node& materials() const { return materials_; }
  // What the drivers of this job declare (their stage and material kinds).
  [[nodiscard]] const std::vector<config::DriverDescription>& drivers() const { return drivers_; }
  [[nodiscard]] uint64_t seed() const { return seed_; }
  [[nodiscard]] const std::filesystem::path& run_dir() const { return run_dir_; }
  // The run was started again with --resume: pick up what an interrupted
  // earlier run of this stage recorded.
  [[nodiscard]] bool resume() const { return resume_; }
  // <run_dir>/<stage>/, created on first use.
  [[nodiscard]] std::filesystem::path stage_dir() const;

  // `params` of a driver stage kind checked against that kind's declared
  // schema, defaults filled: what a driver expects in RunStage. Throws
  // pbms::Error listing what is wrong.
  [[nodiscard]] YAML::Node driver_params(const std::string& kind, const YAML::Node& params) const;

  // Log lines and the stage's progress line (the daemon shows and records them).
  std::function<void(const std::string&)> log;
  std::function<void(int64_t done, int64_t total, const std::string& phase)> progress;

  [[nodiscard]] StageResults& results() { return results_; }

 private:
  Scheduler& scheduler_;
  const config::StageConfig& stage_;
  YAML::Node materials_;
  const std::vector<config::DriverDescription>& drivers_;
  std::filesystem::path run_dir_;
  uint64_t seed_;
  bool resume_;
  StageResults results_;
};

class CouplerStageKind {
 public:
  virtual ~CouplerStageKind() = default;
  virtual void run(CouplerStageContext& ctx) = 0;
};

// What the coupler declares about its own kinds, like a driver's --describe.
config::DriverDescription coupler_description();
std::unique_ptr<CouplerStageKind> create_coupler_stage(const std::string& kind);

}  // namespace pbms::coupler
