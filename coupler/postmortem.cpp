#include "postmortem.hpp"

#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "pbms/io/yaml_file.hpp"
#include "run_record.hpp"

namespace pbms::coupler {
namespace {

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// First "ERROR" line of any LAMMPS log the failing stage left behind.
std::string lammps_error(const std::filesystem::path& stage_dir) {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(stage_dir, ec)) {
    if (e.path().extension() != ".log") continue;
    std::ifstream in(e.path());
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("ERROR", 0) == 0) return line;
    }
  }
  return {};
}

// A failed job exits non-zero even where mpirun itself reported success.
int failure_exit_code(int mpirun_exit_code) {
  return mpirun_exit_code == 0 ? 1 : mpirun_exit_code;
}

// Without a run id, any manifest in the run directory is taken as this job's.
bool manifest_is_ours(const std::filesystem::path& manifest_path, const std::string& run_id) {
  if (run_id.empty()) return true;
  try {
    return std::filesystem::exists(manifest_path) &&
           YAML::LoadFile(manifest_path.string())["run_id"].as<std::string>("") == run_id;
  } catch (const YAML::Exception&) {
    return false;
  }
}

// The failure the coupler recorded in the manifest before the job ended.
void report_recorded_failure(const YAML::Node& f, const std::filesystem::path& run_dir) {
  std::cerr << fmt::format(
      "pbms: run failed: {} rank {}{}{}: {}\n       details: {}\n",
      f["program"].as<std::string>("?"), f["rank"].as<int>(-1),
      f["stage"] ? fmt::format(" in stage '{}'", f["stage"].as<std::string>()) : "",
      f["step"] && f["step"].as<std::int64_t>(-1) >= 0
          ? fmt::format(" at step {}", f["step"].as<std::int64_t>())
          : "",
      f["message"].as<std::string>(""), (run_dir / "log.txt").string());
}

// Who failed where, rebuilt from mpirun's output and the manifest.
struct Failure {
  std::string program = "unknown program";
  int rank = -1;
  int world_rank = -1;
  std::string stage;
  std::int64_t step = -1;
  std::string cause;
};

std::string death_cause(const DeadRank& dead, int mpirun_exit_code) {
  if (dead.signal > 0) {
    return fmt::format("killed by signal {} ({})", dead.signal, dead.signal_name);
  }
  if (dead.world_rank >= 0) return fmt::format("exited with code {}", dead.exit_code);
  return fmt::format("the job ended with exit code {}", mpirun_exit_code);
}

// Not const: yaml-cpp's non-const lookup turns a null `current` into an
// empty map, and the manifest written afterwards has always shown that.
Failure reconstruct_failure(YAML::Node& manifest, const DeadRank& dead, int mpirun_exit_code,
                            const std::filesystem::path& run_dir) {
  Failure failure;
  failure.world_rank = dead.world_rank;
  for (const auto& l : manifest["layout"]) {
    const int first = l["first_world_rank"].as<int>();
    const int n = l["ranks"].as<int>();
    if (dead.world_rank >= first && dead.world_rank < first + n) {
      failure.program = l["program"].as<std::string>();
      failure.rank = dead.world_rank - first;
    }
  }
  failure.stage = manifest["current"]["stage"].as<std::string>("");
  failure.step = manifest["current"]["step"].as<int64_t>(-1);
  failure.cause = death_cause(dead, mpirun_exit_code);
  if (!failure.stage.empty()) {
    if (auto err = lammps_error(run_dir / failure.stage); !err.empty()) {
      failure.cause += ": LAMMPS said: " + err;
    }
  }
  return failure;
}

void report_reconstructed_failure(const Failure& failure) {
  const std::string where =
      failure.stage.empty()
          ? std::string()
          : fmt::format(" during stage '{}' (last reported step {})", failure.stage, failure.step);
  std::cerr << fmt::format("pbms: error: {} rank {} (world rank {}) {}{}\n", failure.program,
                           failure.rank, failure.world_rank, failure.cause, where);
}

void record_failure(YAML::Node& manifest, const Failure& failure,
                    const std::filesystem::path& manifest_path) {
  YAML::Node f;
  f["program"] = failure.program;
  f["rank"] = failure.rank;
  f["world_rank"] = failure.world_rank;
  if (!failure.stage.empty()) f["stage"] = failure.stage;
  if (failure.step >= 0) f["step"] = failure.step;
  f["message"] = failure.cause;
  manifest["failure"] = f;
  manifest["status"] = "failed";
  manifest["finished"] = now_iso8601();
  for (auto s : manifest["stages"]) {
    if (s["name"].as<std::string>() == failure.stage) s["status"] = "failed";
  }
  write_yaml_atomic(manifest_path, manifest, "what ran, with which software");
}

// The summary names the failed stage even though the stage never wrote there.
void record_failed_stage_in_summary(YAML::Node& manifest, const std::string& stage,
                                    const std::filesystem::path& run_dir) {
  const auto summary_path = run_dir / "summary.yaml";
  if (!std::filesystem::exists(summary_path) || stage.empty()) return;
  YAML::Node summary = YAML::LoadFile(summary_path.string());
  for (const auto& s : manifest["stages"]) {
    if (s["name"].as<std::string>() == stage) {
      summary["stages"][stage]["kind"] = s["kind"].as<std::string>();
    }
  }
  summary["stages"][stage]["status"] = "failed";
  write_yaml_atomic(summary_path, summary, kSummaryHeader);
}

}  // namespace

DeadRank parse_mpirun_output(const std::string& text) {
  DeadRank d;
  std::smatch m;
  static const std::regex signal_re(
      R"(process rank (\d+) with PID \d+ on node \S+ exited on signal (\d+) \(([^)]*)\))");
  static const std::regex exit_re(
      R"(Process name:\s*\[\[\d+,\d+\],(\d+)\][\s\S]*?Exit code:\s*(\d+))");
  static const std::regex abort_re(R"(MPI_ABORT was invoked on rank (\d+))");
  if (std::regex_search(text, m, signal_re)) {
    d.world_rank = std::stoi(m[1]);
    d.signal = std::stoi(m[2]);
    d.signal_name = m[3];
  } else if (std::regex_search(text, m, exit_re)) {
    d.world_rank = std::stoi(m[1]);
    d.exit_code = std::stoi(m[2]);
  } else if (std::regex_search(text, m, abort_re)) {
    d.world_rank = std::stoi(m[1]);
  }
  return d;
}

int postmortem(const std::filesystem::path& run_dir, int mpirun_exit_code,
               const std::filesystem::path& mpirun_log, const std::string& run_id) {
  const std::string output = read_file(mpirun_log);
  const auto manifest_path = run_dir / "manifest.yaml";
  const bool ours = manifest_is_ours(manifest_path, run_id);
  std::error_code ec;
  if (ours && std::filesystem::is_directory(run_dir)) {
    std::filesystem::copy_file(mpirun_log, run_dir / "mpirun.log",
                               std::filesystem::copy_options::overwrite_existing, ec);
  }
  if (!ours && std::filesystem::exists(manifest_path)) {
    std::cerr << fmt::format(
        "pbms: the job ended (exit code {}) before this run wrote anything; {} holds another "
        "run and was left as it is; see the messages above\n",
        mpirun_exit_code, run_dir.string());
    return failure_exit_code(mpirun_exit_code);
  }
  if (!ours || !std::filesystem::exists(manifest_path)) {
    std::cerr << fmt::format(
        "pbms: the job ended (exit code {}) before the run directory was "
        "set up; see the messages above\n",
        mpirun_exit_code);
    return failure_exit_code(mpirun_exit_code);
  }
  YAML::Node manifest = YAML::LoadFile(manifest_path.string());
  const std::string status = manifest["status"].as<std::string>("running");
  if (status == "ok") return mpirun_exit_code;
  if (status == "stopped") {  // on request, after a checkpoint: the coupler said how to go on
    std::cerr << fmt::format("pbms: run stopped: {}\n",
                             manifest["failure"]["message"].as<std::string>(""));
    return failure_exit_code(mpirun_exit_code);
  }
  if (status == "failed") {
    report_recorded_failure(manifest["failure"], run_dir);
    return failure_exit_code(mpirun_exit_code);
  }

  // The coupler never got to record the failure: reconstruct it.
  const Failure failure =
      reconstruct_failure(manifest, parse_mpirun_output(output), mpirun_exit_code, run_dir);
  report_reconstructed_failure(failure);
  record_failure(manifest, failure, manifest_path);
  record_failed_stage_in_summary(manifest, failure.stage, run_dir);
  return failure_exit_code(mpirun_exit_code);
}

}  // namespace pbms::coupler
