#include "daemon.hpp"

#include "earlier_run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <thread>

#include <fmt/format.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "capabilities.hpp"
#include "driver_catalog.hpp"
#include "earlier_run.hpp"
#include "part_checkpoints.hpp"
#include "pbms/driver/stop_request.hpp"
#include "pbms/io/yaml_file.hpp"
#include "pbms/mpi/mpmd.hpp"
#include "pbms/progress_meter.hpp"
#include "pbms/units.hpp"
#include "result_cache.hpp"
#include "run_record.hpp"
#include "scheduler.hpp"
#include "stage_references.hpp"
#include "stages/coupler_stage.hpp"

namespace pbms::coupler {
namespace {

using Clock = std::chrono::steady_clock;

// Console output that knows whether a progress line is being refreshed in
// place, so ordinary lines never land on top of it.
class Console {
 public:
  explicit Console(bool terminal) : terminal_(terminal) {}
  void line(const std::string& s) {
    end_progress();
    std::cout << s << "\n" << std::flush;
  }
  void progress(const std::string& s) {
    if (terminal_) {
      std::cout << "\r\033[K" << s << std::flush;
      open_ = true;
    } else {
      std::cout << s << "\n" << std::flush;
    }
  }
  void end_progress() {
    if (open_) std::cout << "\n";
    open_ = false;
  }

 private:
  bool terminal_;
  bool open_ = false;
};

// "stages[3]": where a stage's keys sit in the workflow, for messages.
std::string stage_path(std::size_t index) {
  return fmt::format("stages[{}]", index);
}

class Daemon {
 public:
  explicit Daemon(const DaemonOptions& opt) : opt_(opt), console_(opt.terminal) {}

  int run() {
    install_stop_handlers();
    auto world = mpi::MpmdWorld::join(mpi::Role::kCoupler);
    if (world.local().size() != 1) throw Error("the coupler runs as exactly one process");
    scheduler_ = Scheduler(Scheduler::connect(world), [this](const protocol::Fatal& f) {
      fail(f.program, f.rank, f.stage, f.step, f.message);
    });

    // The launcher validated the workflow, but the daemon checks again: it
    // must never act on a config it has not read itself.
    drivers_ = discover_drivers(opt_.drivers_dir);
    const auto& drivers = drivers_;
    auto loaded = config::load_workflow(opt_.config, drivers);
    std::vector<std::string> problems;
    for (const auto& e : loaded.errors) problems.push_back(e.format());
    if (loaded.workflow) {
      for (const auto& r : opt_.rank_overrides) {
        if (auto err = config::apply_rank_override(*loaded.workflow, drivers, r); !err.empty()) {
          problems.push_back(err);
        }
      }
      std::vector<protocol::Hello> hellos;
      std::vector<int> sizes;
      for (const auto& l : scheduler_.links()) {
        hellos.push_back(l.hello);
        sizes.push_back(l.app.size);
      }
      for (auto& p : check_capabilities(loaded.workflow->stages, hellos, sizes)) {
        problems.push_back(std::move(p));
      }
      // The launcher checked this too; a daemon started by hand, or a run of
      // the same name that began meanwhile, must not cost an earlier result.
      if (auto refusal = existing_run_refusal(*loaded.workflow, existing()); !refusal.empty()) {
        problems.push_back(std::move(refusal));
      }
    }
    if (!problems.empty()) {
      for (const auto& p : problems) std::cerr << "pbms: refused: " << p << "\n";
      scheduler_.welcome(false, fmt::format("{}", fmt::join(problems, "; ")));
      return 1;
    }
    wf_ = std::move(*loaded.workflow);

    std::vector<ProgramLayout> layout{{"coupler", 1, world.coupler().first_world_rank}};
    for (const auto& l : scheduler_.links()) {
      layout.push_back({l.hello.program, l.app.size, l.app.first_world_rank});
    }
    if (opt_.resume) earlier_ = EarlierRun::read(std::filesystem::absolute(wf_.run_dir()));
    record_ = std::make_unique<RunRecord>(wf_, layout, opt_.command_line, existing(), opt_.run_id);
    for (const auto& l : scheduler_.links()) record_->set_software(l.hello.software);
    setup_log();
    scheduler_.welcome(true, "");

    log(fmt::format("run '{}' -> {}", wf_.run_name, record_->dir().string()));
    // `coupler plan` printed these before the job started; the log keeps them.
    for (const auto& w : wf_.warnings) file_log_->warn(w);
    for (const auto& l : scheduler_.links()) {
      log(fmt::format("  {} on {} rank{} (declares: {})", l.hello.program, l.app.size,
                      l.app.size == 1 ? "" : "s", fmt::join(l.hello.capabilities, ", ")));
    }
    try {
      run_stages();
    } catch (const JobStopped&) {
      // The drivers are alive and idle: they end cleanly, and the job ends
      // non-zero through the coupler's exit code.
      scheduler_.shutdown("stopped on request");
      spdlog::shutdown();
      return 3;
    }
    scheduler_.shutdown("workflow complete");
    record_->finished();
    log(fmt::format("done: summary in {}", (record_->dir() / "summary.yaml").string()));
    spdlog::shutdown();
    return 0;
  }

 private:
  // A run stopped on request (stop_request.hpp) once its stage wrote a
  // checkpoint: not a failure, and the job must end cleanly.
  struct JobStopped {};

  void run_stages() {
    for (size_t i = 0; i < wf_.stages.size(); ++i) {
      const auto& name = wf_.stages[i].name;
      if (earlier_ && earlier_->finished(name)) {
        done_[name] = earlier_->results_of(name);
        log(fmt::format("stage {}/{} '{}' finished in the run this one resumes: kept", i + 1,
                        wf_.stages.size(), name));
        continue;
      }
      try {
        run_stage(i);
      } catch (const std::exception& e) {
        fail("coupler", 0, wf_.stages[i].name, -1, e.what());
      }
    }
  }

  [[nodiscard]] int keep_checkpoints() const {
    const YAML::Node c = wf_.resolved["checkpoint"];
    return c && c["keep"] ? c["keep"].as<int>() : 2;
  }

  [[nodiscard]] ExistingRun existing() const {
    if (opt_.resume) return ExistingRun::kResume;
    return opt_.overwrite ? ExistingRun::kOverwrite : ExistingRun::kRefuse;
  }

  void setup_log() {
    auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(record_->log_path().string());
    file->set_pattern("[%Y-%m-%d %H:%M:%S] %v");
    file_log_ = std::make_shared<spdlog::logger>("run", file);
    file_log_->flush_on(spdlog::level::info);
  }

  void log(const std::string& s) {
    console_.line("pbms: " + s);
    if (file_log_) file_log_->info(s);
  }

  // One stage's progress: a line refreshed on the console, about every
  // 10 % in log.txt, and the manifest's `current` block.
  class StageProgress {
   public:
    StageProgress(Daemon& d, std::string stage, const std::string& item)
        : d_(d),
          stage_(std::move(stage)),
          console_(stage_, d.opt_.terminal, item),
          file_(stage_, false, item) {}
    void show(int64_t step, int64_t total, double sim_time_ps, const std::string& phase) {
      d_.record_->progress(stage_, step, total, std::max(sim_time_ps, 0.0));
      if (auto line = console_.update(step, total, sim_time_ps, phase, elapsed())) {
        d_.console_.progress(*line);
      }
      if (auto line = file_.update(step, total, sim_time_ps, phase, elapsed())) {
        if (d_.file_log_) d_.file_log_->info(*line);
      }
    }
    [[nodiscard]] double elapsed() const {
      return std::chrono::duration<double>(Clock::now() - t0_).count();
    }

   private:
    Daemon& d_;
    std::string stage_;
    ProgressMeter console_, file_;
    Clock::time_point t0_ = Clock::now();
  };

  void run_stage(size_t index) {
    const auto& stage = wf_.stages[index];
    if (stage.program == config::kCouplerProgram) {
      run_coupler_stage(index);
      return;
    }
    protocol::RunStage rs;
    rs.index = static_cast<int32_t>(index);
    rs.name = stage.name;
    rs.kind = stage.kind;
    rs.params_yaml = yaml_text(resolve_references(stage.params, done_, stage_path(index)));
    rs.materials_yaml = yaml_text(resolve_materials(wf_.materials, done_));
    rs.run_dir = record_->dir().string();
    rs.seed = wf_.seed;
    if (wf_.resolved["checkpoint"]) rs.checkpoint_yaml = yaml_text(wf_.resolved["checkpoint"]);
    // A stage the resumed run was running goes on from its newest complete
    // checkpoint (the manifest lists only complete ones).
    const std::vector<std::string> resume_files =
        opt_.resume ? record_->newest_checkpoint(stage.name) : std::vector<std::string>{};
    if (!resume_files.empty()) rs.resume_from = resume_files.front();
    record_->stage_started(stage);
    if (!rs.resume_from.empty()) {
      log(fmt::format("stage '{}' goes on from its checkpoint {}", stage.name, rs.resume_from));
    }
    log(fmt::format("stage {}/{} '{}' ({}) on {}", index + 1, wf_.stages.size(), stage.name,
                    stage.kind, stage.program));
    const std::optional<std::string> identity = cache_identity_of(stage, rs);
    const ResultCache cache(std::filesystem::path(wf_.output_dir) / ".cache");
    if (identity) {
      if (auto hit = cache.find(*identity, record_->dir())) {
        log(fmt::format("stage '{}' reused from the cache ({}), computed there in {}", stage.name,
                        cache.entry_dir(*identity).string(), format_duration(hit->wall_s)));
        finish_stage(stage, std::move(*hit));
        return;
      }
    }
    // A stop request (SIGTERM, SIGUSR1) reaches the drivers too: the
    // coupler waits for the stage to write its checkpoint and stop.
    const StopWindow stop_window;
    const auto request = scheduler_.submit(stage.program, rs);
    // Partners (the MPM part of a concurrent stage) start at the same time:
    // their parts exchange data with the main one rank to rank.
    std::map<protocol::RequestId, std::optional<protocol::StageDone>> partners;
    // Each part writes its own file of a checkpoint (the main part first).
    std::map<protocol::RequestId, std::size_t> part_of{{request, 0}};
    const auto& partner_kinds = spec_of(stage.kind).partners;
    for (std::size_t k = 0; k < partner_kinds.size(); ++k) {
      protocol::RunStage prs = rs;
      prs.kind = partner_kinds[k].kind;
      if (!rs.resume_from.empty()) prs.resume_from = resume_files.at(k + 1);
      const auto id = scheduler_.submit(partner_kinds[k].program, prs);
      partners[id] = std::nullopt;
      part_of[id] = k + 1;
    }
    PartCheckpoints checkpoints(part_of.size());

    StageProgress progress(*this, stage.name, "step");
    // Any failed part ends the run: the other parts would wait for it. A
    // part stopped on request is the exception: the others stop at the same
    // step, and their files complete the checkpoint it wrote.
    std::optional<protocol::StageFailed> stopped;
    const auto on_failure = [&](const protocol::StageFailed& f) {
      if (!f.reason.starts_with(kStoppedBySignal))
        fail(f.program, f.rank, f.stage, f.step, f.reason);
      if (!stopped) stopped = f;
      if (partners.count(f.request) != 0) partners[f.request] = protocol::StageDone{};
    };
    auto on_answer = [&](const Answer& a) {
      if (const auto* p = std::get_if<protocol::Progress>(&a)) {
        if (!p->checkpoint.empty()) {
          const auto files = checkpoints.add(part_of.at(p->request), p->step, p->checkpoint);
          if (files) {
            record_->checkpoint_written(stage.name, p->step, *files, keep_checkpoints());
            if (file_log_) {
              file_log_->info("  checkpoint after step {}: {}", p->step, fmt::join(*files, ", "));
            }
          }
        } else if (p->request == request) {
          progress.show(p->step, p->total_steps, p->sim_time_ps, p->phase);
        }
      } else if (const auto* f = std::get_if<protocol::StageFailed>(&a)) {
        on_failure(*f);
      } else if (const auto* d = std::get_if<protocol::StageDone>(&a)) {
        if (partners.count(d->request) != 0) partners[d->request] = *d;
      }
    };
    const Answer answer = scheduler_.wait_for(request, on_answer);
    if (const auto* f = std::get_if<protocol::StageFailed>(&answer)) on_failure(*f);
    for (auto& [id, part] : partners) {
      if (!part) on_answer(scheduler_.wait_for(id, on_answer));
    }
    // A workflow stage without its result leaves later stages without their
    // inputs: it ends the run, though the driver could go on.
    if (stopped)
      fail(stopped->program, stopped->rank, stopped->stage, stopped->step, stopped->reason);
    auto done = std::get<protocol::StageDone>(answer);
    for (auto& [id, part] : partners) merge_part(done.results, *part);
    console_.end_progress();
    if (identity) cache.store(*identity, done, record_->dir());
    log(fmt::format("stage '{}' finished in {}", stage.name, format_duration(done.wall_s)));
    finish_stage(stage, std::move(done));
    if (stop_requested()) {
      fail(stage.program, 0, stage.name, -1,
           fmt::format("{} (SIGTERM or SIGUSR1: a wall-time limit?) as stage "
                       "'{}' finished",
                       kStoppedBySignal, stage.name));
    }
  }

  // A stage the coupler runs itself: it sends its own requests through the
  // scheduler and shows one progress line.
  void run_coupler_stage(size_t index) {
    const auto& stage = wf_.stages[index];
    config::StageConfig resolved = stage;
    resolved.params = resolve_references(stage.params, done_, stage_path(index));
    record_->stage_started(stage);
    log(fmt::format("stage {}/{} '{}' ({}) on the coupler, using {}", index + 1, wf_.stages.size(),
                    stage.name, stage.kind, fmt::join(stage.drivers, ", ")));
    CouplerStageContext ctx(scheduler_, resolved, resolve_materials(wf_.materials, done_), drivers_,
                            record_->dir(), wf_.seed, opt_.resume);
    StageProgress progress(*this, stage.name, "evaluation");
    ctx.log = [&](const std::string& line) { log(fmt::format("  {}: {}", stage.name, line)); };
    ctx.progress = [&](int64_t n, int64_t total, const std::string& phase) {
      progress.show(n, total, -1.0, phase);  // no simulated time
    };
    create_coupler_stage(stage.kind)->run(ctx);
    console_.end_progress();
    protocol::StageDone done;
    done.stage = stage.name;
    done.wall_s = progress.elapsed();
    done.results = std::move(ctx.results());
    log(fmt::format("stage '{}' finished in {}", stage.name, format_duration(done.wall_s)));
    finish_stage(stage, std::move(done));
  }

  const config::StageKindSpec& spec_of(const std::string& kind) const {
    for (const auto& d : drivers_) {
      if (const auto* s = d.stage_kind(kind)) return *s;
    }
    throw Error(fmt::format("no driver declares stage kind '{}'", kind));
  }

  // A partner's scalars, tables and files join the main part's; the kinds
  // keep their key names apart.
  static void merge_part(StageResults& into, const protocol::StageDone& part) {
    const StageResults& r = part.results;
    into.scalars.insert(into.scalars.end(), r.scalars.begin(), r.scalars.end());
    into.columns.insert(into.columns.end(), r.columns.begin(), r.columns.end());
    into.files.insert(into.files.end(), r.files.begin(), r.files.end());
    into.attributes.insert(r.attributes.begin(), r.attributes.end());
    into.warnings.insert(into.warnings.end(), r.warnings.begin(), r.warnings.end());
  }

  void finish_stage(const config::StageConfig& stage, protocol::StageDone done) {
    record_->stage_finished(stage, done.results, done.wall_s);
    for (const auto& s : done.results.scalars) {
      const std::string err =
          std::isfinite(s.std_error) ? fmt::format(" ± {:.4g}", s.std_error) : "";
      log(fmt::format("  {} = {:.6g}{} {}", s.key, s.value, err, s.unit));
    }
    for (const auto& w : done.results.warnings) log(fmt::format("  warning: {}", w));
    done_[stage.name] = std::move(done.results);
  }

  // What decides a cacheable stage's result, or nothing for other stages.
  // Only the materials the stage names count, so that editing another
  // material (a refit's potential) keeps the MD results.
  std::optional<std::string> cache_identity_of(const config::StageConfig& stage,
                                               const protocol::RunStage& rs) const {
    const config::StageKindSpec* spec = nullptr;
    for (const auto& d : drivers_) {
      if (!spec) spec = d.stage_kind(stage.kind);
    }
    if (!spec || !spec->cacheable) return std::nullopt;
    const YAML::Node all = YAML::Load(rs.materials_yaml);
    YAML::Node own(YAML::NodeType::Map);
    for (const auto& p : spec->params) {
      const YAML::Node name = stage.params[p.name];
      if (p.names_material && name && name.IsScalar()) own[name.Scalar()] = all[name.Scalar()];
    }
    protocol::RunStage keyed = rs;
    keyed.materials_yaml = yaml_text(own);
    const auto& link = scheduler_.link(stage.program);
    return cache_identity(keyed, link.hello.software, file_digest(opt_.drivers_dir / stage.program),
                          material_files(own));
  }

  // "path: digest" of every file the materials read (their kind's file
  // fields), so that a cache entry follows the contents, not the name.
  [[nodiscard]] std::vector<std::string> material_files(const YAML::Node& materials) const {
    std::vector<std::string> out;
    for (const auto& m : materials) {
      const YAML::Node kind = m.second["kind"];
      const config::MaterialKindSpec* spec =
          kind && kind.IsScalar() ? config::find_material_kind(drivers_, kind.Scalar()) : nullptr;
      if (!spec) continue;
      for (const auto& p : spec->params) {
        const YAML::Node path = m.second[p.name];
        if (p.kind != config::ParamKind::kFile || !path || !path.IsScalar()) continue;
        out.push_back(fmt::format("{}: {}", path.Scalar(), file_digest(path.Scalar())));
      }
    }
    return out;
  }

  [[noreturn]] void fail(const std::string& program, int rank, const std::string& stage,
                         int64_t step, const std::string& message) {
    console_.end_progress();
    const std::string where = stage.empty()
                                  ? std::string()
                                  : fmt::format(" in stage '{}'{}", stage,
                                                step >= 0 ? fmt::format(" at step {}", step) : "");
    const bool stopped = message.starts_with(kStoppedBySignal);
    const std::string text =
        stopped ? fmt::format("{}{}: {}; to go on from there: ./pbms run {} --resume", program,
                              where, message, opt_.config)
                : fmt::format("{} rank {} failed{}: {}", program, rank, where, message);
    std::cerr << (stopped ? "pbms: stopped: " : "pbms: error: ") << text << "\n" << std::flush;
    if (file_log_) file_log_->error(text);
    if (stopped) {
      record_->failed(
          program, rank, stage, step,
          fmt::format("{}; to go on from there: ./pbms run {} --resume", message, opt_.config),
          "stopped");
      throw JobStopped{};
    }
    try {
      record_->failed(program, rank, stage, step, message);
    } catch (const std::exception& e) {
      std::cerr << "pbms: could not record the failure: " << e.what() << "\n";
    }
    spdlog::shutdown();
    MPI_Abort(MPI_COMM_WORLD, 2);
    std::_Exit(2);
  }

  DaemonOptions opt_;
  Console console_;
  Scheduler scheduler_;
  std::vector<config::DriverDescription> drivers_;
  config::Workflow wf_;
  std::unique_ptr<RunRecord> record_;
  std::shared_ptr<spdlog::logger> file_log_;
  std::map<std::string, StageResults> done_;
  std::optional<EarlierRun> earlier_;  // with --resume: the run this one continues
};

}  // namespace

int run_daemon(const DaemonOptions& opt) {
  Daemon d(opt);
  return d.run();
}

}  // namespace pbms::coupler
