// The public API for writing a driver: a driver is a set of StageKind
// classes, registered by name (like LAMMPS styles), plus one call to
// run_driver() in main(). Everything MPI and protocol related stays behind
// StageContext.
#pragma once

#include <mpi.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/driver/checkpoint_plan.hpp"
#include "pbms/results.hpp"

namespace pbms {

class DriverRuntime;  // internal

// What a running stage sees of the world.
class StageContext {
 public:
  StageContext(DriverRuntime& runtime, int64_t request, std::string stage, std::string kind,
               const YAML::Node& params, const YAML::Node& materials, std::filesystem::path run_dir,
               uint64_t seed);

  [[nodiscard]] const std::string& stage() const { return stage_; }
  [[nodiscard]] const std::string& kind() const { return kind_; }
  [[nodiscard]] const YAML::Node& params() const { return params_; }
  // The resolved entry of `materials:` called `name`.
  [[nodiscard]] YAML::Node material(const std::string& name) const;
  // The one the stage's `material` key names.
  [[nodiscard]] YAML::Node material() const;
  [[nodiscard]] uint64_t seed() const { return seed_; }

  // The ranks that run this request: all ranks of the program, or the
  // request's group when the coupler split the driver into rank groups.
  [[nodiscard]] MPI_Comm comm() const;
  [[nodiscard]] int rank() const;
  [[nodiscard]] int size() const;
  // Intercommunicator to another driver program of this job (rank-to-rank
  // exchange), or MPI_COMM_NULL if that program is not running.
  [[nodiscard]] MPI_Comm peer(const std::string& program) const;

  [[nodiscard]] const std::filesystem::path& run_dir() const { return run_dir_; }
  // <run_dir>/<stage>/, created on first use; for files the stage writes.
  [[nodiscard]] std::filesystem::path stage_dir() const;

  // Call from every rank as the stage advances; rank 0 reports to the
  // coupler at most every 1 % or 0.5 s. `step` also labels failures.
  void progress(int64_t step, int64_t total_steps, double sim_time_ps, const std::string& phase);

  // The workflow's checkpoints, and the file to resume from.
  [[nodiscard]] const CheckpointPlan& checkpoint_plan() const { return checkpoint_plan_; }
  void set_checkpoint_plan(CheckpointPlan plan) { checkpoint_plan_ = std::move(plan); }
  // Rank 0: tells the coupler that the checkpoint `file` (relative to the
  // run directory) after `step` is complete.
  void checkpoint_written(int64_t step, double sim_time_ps, const std::string& file);

  // Results are taken from rank 0 when run() returns.
  [[nodiscard]] StageResults& results() { return results_; }

  // Collective over comm(): if any rank passes `failed`, every rank throws
  // StageFailure with the reason of the lowest such rank. For checks that one
  // rank can make alone (a NaN in its particles) but that must fail the
  // request on all ranks together.
  void fail_together(bool failed, const std::string& reason) const;

 private:
  DriverRuntime& runtime_;
  int64_t request_;
  std::string stage_, kind_;
  YAML::Node params_, materials_;
  std::filesystem::path run_dir_;
  uint64_t seed_;
  StageResults results_;
  CheckpointPlan checkpoint_plan_;
  std::chrono::steady_clock::time_point created_ = std::chrono::steady_clock::now();
  double last_report_s_ = -1.0;
  int64_t last_report_step_ = -1;
};

class StageKind {
 public:
  virtual ~StageKind() = default;
  // Run on every rank of the driver; throw pbms::Error to fail the stage.
  virtual void run(StageContext& ctx) = 0;
};

// Stage kinds by name. Each entry carries the spec the driver declares.
class StageRegistry {
 public:
  using Factory = std::function<std::unique_ptr<StageKind>()>;
  void add(config::StageKindSpec spec, Factory factory);
  template <typename T>
  void add() {
    add(T::spec(), [] { return std::make_unique<T>(); });
  }
  [[nodiscard]] std::unique_ptr<StageKind> create(const std::string& kind) const;
  [[nodiscard]] std::vector<config::StageKindSpec> specs() const;

  // A material kind the driver's stages take, published with the stages.
  void add_material(config::MaterialKindSpec spec) { materials_.push_back(std::move(spec)); }
  [[nodiscard]] const std::vector<config::MaterialKindSpec>& materials() const {
    return materials_;
  }

 private:
  std::map<std::string, std::pair<config::StageKindSpec, Factory>> entries_;
  std::vector<config::MaterialKindSpec> materials_;
};

struct DriverInfo {
  std::string program;                                        // "md_driver"
  std::string short_name;                                     // "md"
  std::vector<std::pair<std::string, std::string>> software;  // name -> version
};

// main() of every driver. Handles --describe and --help without MPI;
// otherwise joins the MPMD job, shakes hands with the coupler and serves
// stages until shut down. Returns the process exit code.
int run_driver(int argc, char** argv, const DriverInfo& info, const StageRegistry& registry);

// The step and stage a failure on this rank should be reported with.
void set_current_step(int64_t step);

// Reports a failure of this rank to the coupler (program, rank, stage, step
// are added) and ends the whole job. For failures detected outside the
// normal exception path, e.g. a library calling MPI_Finalize on error.
[[noreturn]] void abort_job(const std::string& message);

// A library that handles its own errors by calling MPI_Finalize() and
// exit() (LAMMPS without exceptions) would hang an MPMD job: MPI_Finalize
// waits for every program. Drivers link pbms_finalize_guard, which turns
// such a call into abort_job(); `describe` supplies the library's message.
void set_unexpected_finalize_handler(std::string (*describe)());

}  // namespace pbms
