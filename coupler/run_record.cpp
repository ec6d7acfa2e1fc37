#include "run_record.hpp"

#include <unistd.h>

#include <chrono>
#include <ctime>
#include <map>
#include <optional>

#include <H5public.h>
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "earlier_run.hpp"
#include "pbms/io/hdf5.hpp"
#include "pbms/io/yaml_file.hpp"
#include "pbms/protocol/messages.hpp"
#include "pbms/version.hpp"

namespace pbms::coupler {
namespace {

// A checkpoint's files: the main part's and any other part's.
void remove_checkpoint(const std::filesystem::path& dir, const YAML::Node& entry) {
  std::error_code ec;
  std::filesystem::remove(dir / entry["file"].as<std::string>(), ec);
  for (const auto& part : entry["parts"]) std::filesystem::remove(dir / part.as<std::string>(), ec);
}

double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

YAML::Node scalar_node(const ScalarResult& s) {
  YAML::Node n;
  n["value"] = s.value;
  n["unit"] = s.unit;
  if (std::isfinite(s.std_error)) n["std_error"] = s.std_error;
  return n;
}

}  // namespace

std::string now_iso8601() {
  const auto t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  localtime_r(&t, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S%z", &tm);
  return buf;
}

namespace {

// A resumed run must be the run it continues: its finished stages and its
// checkpoints hold the results of that config, not of this one.
std::string resume_refusal(const config::Workflow& wf) {
  const auto dir = std::filesystem::absolute(wf.run_dir()).lexically_normal();
  const auto earlier = EarlierRun::read(dir);
  if (!earlier) return {};
  const std::string diff = first_difference(earlier->config(), wf.resolved);
  if (diff.empty()) return {};
  ConfigError e;
  e.file = wf.source_file;
  e.line = wf.run_name_line;
  e.column = wf.run_name_column;
  e.key_path = "run.name";
  e.message = fmt::format(
      "--resume continues the run in '{}', but the config has changed since: {}. Its finished "
      "stages and checkpoints belong to the config it ran",
      dir.string(), diff);
  std::string out = e.format();
  out += fmt::format("\n  to start it afresh:  ./pbms run {} --overwrite", wf.source_file);
  out += fmt::format("\n  to keep both:        give this run a new run.name in {}", wf.source_file);
  return out;
}

}  // namespace

std::string existing_run_refusal(const config::Workflow& wf, ExistingRun existing) {
  if (existing == ExistingRun::kResume) return resume_refusal(wf);
  if (existing != ExistingRun::kRefuse) return {};
  const auto dir = std::filesystem::absolute(wf.run_dir()).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec) || std::filesystem::is_empty(dir, ec)) return {};
  std::vector<std::string> resumable;
  for (const auto& s : wf.stages) {
    if (s.program == config::kCouplerProgram) resumable.push_back(fmt::format("'{}'", s.name));
  }
  ConfigError e;
  e.file = wf.source_file;
  e.line = wf.run_name_line;
  e.column = wf.run_name_column;
  e.key_path = "run.name";
  e.message = fmt::format(
      "the run directory '{}' holds an earlier run (run.name '{}'), which this run would "
      "replace; it was left as it is",
      dir.string(), wf.run_name);
  std::string out = e.format();
  out += fmt::format("\n  to replace it:   ./pbms run {} --overwrite", wf.source_file);
  out += fmt::format("\n  to keep both:    give this run a new run.name in {}", wf.source_file);
  out += fmt::format(
      "\n  to continue it:  ./pbms run {} --resume (its finished stages are kept{}; a dpd_run "
      "goes on from its newest checkpoint, others start again)",
      wf.source_file,
      resumable.empty()
          ? ""
          : fmt::format(", and {} replay{} what {} recorded", fmt::join(resumable, ", "),
                        resumable.size() == 1 ? "s" : "", resumable.size() == 1 ? "it" : "they"));
  return out;
}

RunRecord::RunRecord(const config::Workflow& wf, const std::vector<ProgramLayout>& layout,
                     const std::string& command_line, ExistingRun existing,
                     const std::string& run_id)
    : dir_(std::filesystem::absolute(wf.run_dir())) {
  // A run directory describes exactly one run, and nothing in it is deleted
  // unless the user asked (--overwrite). A resumed run keeps it: its stages
  // pick up what they recorded there.
  if (existing == ExistingRun::kOverwrite) std::filesystem::remove_all(dir_);
  std::filesystem::create_directories(dir_.parent_path());
  const bool created = std::filesystem::create_directory(dir_);
  if (!created && existing == ExistingRun::kRefuse && !std::filesystem::is_empty(dir_)) {
    throw Error(existing_run_refusal(wf, existing));
  }
  std::optional<EarlierRun> earlier;
  if (existing == ExistingRun::kResume) earlier = EarlierRun::read(dir_);
  write_yaml_atomic(dir_ / "config.yaml", wf.resolved,
                    fmt::format("resolved from {}: defaults filled in, quantities in metal units",
                                wf.source_file));

  char host[256] = "unknown";
  gethostname(host, sizeof host - 1);
  unsigned maj = 0, min = 0, rel = 0;
  H5get_libversion(&maj, &min, &rel);
  char mpi_version[MPI_MAX_LIBRARY_VERSION_STRING];
  int len = 0;
  MPI_Get_library_version(mpi_version, &len);
  std::string mpi(mpi_version, static_cast<size_t>(len));
  if (auto nl = mpi.find_first_of(",\n"); nl != std::string::npos) mpi.resize(nl);

  manifest_["pbms_version"] = version();
  manifest_["git_hash"] = git_hash();
  manifest_["protocol_version"] = static_cast<int>(protocol::kProtocolVersion);
  manifest_["config"] = std::filesystem::absolute(wf.source_file).string();
  manifest_["command"] = command_line;
  if (!run_id.empty()) manifest_["run_id"] = run_id;
  manifest_["host"] = std::string(host);
  manifest_["started"] = now_iso8601();
  manifest_["status"] = "running";
  manifest_["software"]["mpi"] = mpi;
  manifest_["software"]["hdf5"] = fmt::format("{}.{}.{}", maj, min, rel);
  for (const auto& l : layout) {
    YAML::Node n;
    n["program"] = l.program;
    n["ranks"] = l.ranks;
    n["first_world_rank"] = l.first_world_rank;
    manifest_["layout"].push_back(n);
  }
  for (const auto& s : wf.stages) {
    YAML::Node n;
    n["name"] = s.name;
    n["kind"] = s.kind;
    n["program"] = s.program;
    n["status"] = "pending";
    // A stage the earlier run finished keeps its record; one it was
    // running keeps its checkpoints, to restart from.
    if (earlier && earlier->finished(s.name)) n = YAML::Clone(earlier->stage_entry(s.name));
    if (earlier && !earlier->finished(s.name) && earlier->stage_entry(s.name)["checkpoints"]) {
      n["checkpoints"] = YAML::Clone(earlier->stage_entry(s.name)["checkpoints"]);
    }
    manifest_["stages"].push_back(n);
  }
  for (const auto& w : wf.warnings) manifest_["config_warnings"].push_back(w);
  if (earlier) {
    for (const auto& r : earlier->manifest()["resumed"]) manifest_["resumed"].push_back(r);
    manifest_["resumed"].push_back(now_iso8601());
    if (earlier->manifest()["started"]) manifest_["started"] = earlier->manifest()["started"];
  }
  summary_["run"] = wf.run_name;
  summary_["stages"] = YAML::Node(YAML::NodeType::Map);
  for (const auto& s : wf.stages) {
    if (earlier && earlier->finished(s.name)) {
      summary_["stages"][s.name] = YAML::Clone(earlier->summary()["stages"][s.name]);
    }
  }
  write_manifest();
  write_summary();
}

void RunRecord::set_software(const std::vector<std::string>& items) {
  for (const auto& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) continue;
    manifest_["software"][item.substr(0, eq)] = item.substr(eq + 1);
  }
  write_manifest();
}

void RunRecord::stage_started(const config::StageConfig& stage) {
  for (auto n : manifest_["stages"]) {
    if (n["name"].as<std::string>() == stage.name) n["status"] = "running";
  }
  YAML::Node cur;
  cur["stage"] = stage.name;
  cur["step"] = 0;
  manifest_["current"] = cur;
  write_manifest();
}

void RunRecord::progress(const std::string& stage, int64_t step, int64_t total,
                         double sim_time_ps) {
  manifest_["current"]["stage"] = stage;
  manifest_["current"]["step"] = step;
  manifest_["current"]["total_steps"] = total;
  manifest_["current"]["sim_time_ps"] = sim_time_ps;
  // Rewriting the manifest on every report would be wasteful; once a second
  // is enough for a post-mortem to name the step.
  const double now = wall_now();
  if (now - last_manifest_write_ >= 1.0) write_manifest();
}

void RunRecord::stage_finished(const config::StageConfig& stage, const StageResults& results,
                               double wall_s) {
  write_stage_results(dir_ / "results.h5", stage.name, stage.kind, "ok", results, wall_s);
  YAML::Node s;
  s["kind"] = stage.kind;
  s["status"] = "ok";
  s["wall_s"] = wall_s;
  s["results"] = YAML::Node(YAML::NodeType::Map);
  for (const auto& r : results.scalars) s["results"][r.key] = scalar_node(r);
  for (const auto& w : results.warnings) s["warnings"].push_back(w);
  summary_["stages"][stage.name] = s;
  write_summary();
  for (auto n : manifest_["stages"]) {
    if (n["name"].as<std::string>() == stage.name) {
      // A finished stage is not resumed: its checkpoints are done with.
      for (const auto& c : n["checkpoints"]) remove_checkpoint(dir_, c);
      n.remove("checkpoints");
      n["status"] = "ok";
      n["wall_s"] = wall_s;
      for (const auto& f : results.files) n["files"].push_back(f);
      for (const auto& w : results.warnings) n["warnings"].push_back(w);
    }
  }
  manifest_.remove("current");
  write_manifest();
}

void RunRecord::stage_failed(const std::string& stage, const std::string& kind,
                             const std::string& status) {
  YAML::Node s;
  s["kind"] = kind;
  s["status"] = status;
  s["results"] = YAML::Node(YAML::NodeType::Map);
  summary_["stages"][stage] = s;
  write_summary();
  for (auto n : manifest_["stages"]) {
    if (n["name"].as<std::string>() == stage) n["status"] = status;
  }
}

void RunRecord::checkpoint_written(const std::string& stage, int64_t step,
                                   const std::vector<std::string>& files, int keep) {
  for (auto n : manifest_["stages"]) {
    if (n["name"].as<std::string>() != stage) continue;
    YAML::Node c;
    c["step"] = step;
    c["file"] = files.at(0);
    for (std::size_t k = 1; k < files.size(); ++k) c["parts"].push_back(files[k]);
    n["checkpoints"].push_back(c);
    // Listed first, deleted after: a crash between the two leaves an extra
    // file, never a listed one that is gone.
    write_manifest();
    YAML::Node kept(YAML::NodeType::Sequence);
    const auto count = static_cast<int>(n["checkpoints"].size());
    for (int k = 0; k < count; ++k) {
      const YAML::Node old = n["checkpoints"][k];
      if (k < count - keep) {
        remove_checkpoint(dir_, old);
      } else {
        kept.push_back(old);
      }
    }
    n["checkpoints"] = kept;
  }
  write_manifest();
}

std::vector<std::string> RunRecord::newest_checkpoint(const std::string& stage) const {
  for (const auto& n : manifest_["stages"]) {
    if (n["name"].as<std::string>() != stage || !n["checkpoints"] || n["checkpoints"].size() == 0) {
      continue;
    }
    const YAML::Node last = n["checkpoints"][n["checkpoints"].size() - 1];
    std::vector<std::string> files{(dir_ / last["file"].as<std::string>()).string()};
    for (const auto& part : last["parts"])
      files.push_back((dir_ / part.as<std::string>()).string());
    return files;
  }
  return {};
}

void RunRecord::failed(const std::string& program, int rank, const std::string& stage, int64_t step,
                       const std::string& message, const std::string& status) {
  YAML::Node f;
  f["program"] = program;
  f["rank"] = rank;
  if (!stage.empty()) f["stage"] = stage;
  if (step >= 0) f["step"] = step;
  f["message"] = message;
  manifest_["failure"] = f;
  manifest_["status"] = status;
  manifest_["finished"] = now_iso8601();
  if (!stage.empty()) {
    std::string kind;
    for (const auto& n : manifest_["stages"]) {
      if (n["name"].as<std::string>() == stage) kind = n["kind"].as<std::string>();
    }
    stage_failed(stage, kind, status);
  }
  write_manifest();
}

void RunRecord::finished() {
  manifest_["status"] = "ok";
  manifest_["finished"] = now_iso8601();
  write_manifest();
}

void RunRecord::write_manifest() {
  write_yaml_atomic(dir_ / "manifest.yaml", manifest_, "what ran, with which software");
  last_manifest_write_ = wall_now();
}

void RunRecord::write_summary() {
  write_yaml_atomic(dir_ / "summary.yaml", summary_, kSummaryHeader);
}

void write_stage_results(const std::filesystem::path& file, const std::string& stage,
                         const std::string& kind, const std::string& status,
                         const StageResults& results, double wall_s) {
  h5::Handle f = h5::open_or_create(file.string());
  h5::delete_link_if_exists(f.id(), stage);
  h5::Handle g = h5::require_group(f.id(), stage);
  h5::write_attribute(g.id(), "kind", kind);
  h5::write_attribute(g.id(), "status", status);
  h5::write_attribute(g.id(), "wall_s", wall_s);
  for (const auto& [k, v] : results.attributes) h5::write_attribute(g.id(), k, v);
  for (const auto& s : results.scalars) {
    h5::write_scalar(g.id(), s.key, s.value, s.unit);
    if (std::isfinite(s.std_error)) {
      h5::Handle ds(H5Dopen2(g.id(), s.key.c_str(), H5P_DEFAULT), H5Dclose);
      h5::write_attribute(ds.id(), "std_error", s.std_error);
    }
  }
  for (const auto& c : results.columns) {
    h5::Handle t = h5::require_group(g.id(), c.table);
    h5::write_vector(t.id(), c.name, c.data, c.unit);
  }
  H5Fflush(f.id(), H5F_SCOPE_GLOBAL);
}

}  // namespace pbms::coupler
