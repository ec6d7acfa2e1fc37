// The files of one run directory that the coupler owns: the resolved config,
// manifest.yaml, summary.yaml and results.h5. Each write leaves every file
// complete and readable, so a crash at any moment loses nothing written
// before it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/workflow.hpp"
#include "pbms/mpi/mpmd.hpp"
#include "pbms/results.hpp"

namespace pbms::coupler {

struct ProgramLayout {
  std::string program;
  int ranks = 0;
  int first_world_rank = 0;
};

// What a run does with a run directory that holds an earlier run.
enum class ExistingRun {
  kRefuse,     // the default: stop, change nothing
  kOverwrite,  // --overwrite: delete it and start afresh
  kResume,     // --resume: keep it; stages pick up what they recorded there
};

// Empty when `wf` may start with `existing`; otherwise the refusal to print:
// a file:line:col error at run.name naming the run directory, then one
// line per way out (--overwrite, a new run.name, --resume where a stage
// resumes). A directory that is missing or empty holds no earlier run.
std::string existing_run_refusal(const config::Workflow& wf, ExistingRun existing);

class RunRecord {
 public:
  // Creates the run directory and writes config.yaml and a manifest with
  // status "running". An earlier run there is deleted only with kOverwrite,
  // kept with kResume, and with kRefuse throws pbms::Error (the directory is
  // claimed atomically, so two runs of one name cannot both start).
  // `run_id` marks the manifest as this job's for `coupler postmortem`.
  RunRecord(const config::Workflow& wf, const std::vector<ProgramLayout>& layout,
            const std::string& command_line, ExistingRun existing = ExistingRun::kRefuse,
            const std::string& run_id = {});

  [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }
  [[nodiscard]] std::filesystem::path log_path() const { return dir_ / "log.txt"; }

  // Records "name=version" items a driver reported in its Hello.
  void set_software(const std::vector<std::string>& items);
  void stage_started(const config::StageConfig& stage);
  void progress(const std::string& stage, int64_t step, int64_t total, double sim_time_ps);
  void stage_finished(const config::StageConfig& stage, const StageResults& results, double wall_s);
  void stage_failed(const std::string& stage, const std::string& kind,
                    const std::string& status = "failed");
  // A complete checkpoint of `stage` after `step`, one file per part of the
  // stage (the main part's first): listed under the stage in the manifest;
  // then all but the newest `keep` are deleted.
  void checkpoint_written(const std::string& stage, int64_t step,
                          const std::vector<std::string>& files, int keep);
  // The files of the newest complete checkpoint of `stage` the manifest
  // lists (absolute paths, the main part's first), or none.
  [[nodiscard]] std::vector<std::string> newest_checkpoint(const std::string& stage) const;
  // `status` is "failed", or "stopped" for a run stopped on request.
  void failed(const std::string& program, int rank, const std::string& stage, int64_t step,
              const std::string& message, const std::string& status = "failed");
  void finished();

 private:
  void write_manifest();
  void write_summary();

  std::filesystem::path dir_;
  YAML::Node manifest_;
  YAML::Node summary_;
  double last_manifest_write_ = -1.0;
};

// Stores one stage's results in results.h5: a group per stage with units as
// attributes. Opens and closes the file each time.
void write_stage_results(const std::filesystem::path& file, const std::string& stage,
                         const std::string& kind, const std::string& status,
                         const StageResults& results, double wall_s);

std::string now_iso8601();

// Header comment of every summary.yaml, wherever it is written.
inline constexpr const char* kSummaryHeader =
    "scalar results per stage: {value, unit}; moduli in GPa, else metal units";

}  // namespace pbms::coupler
