#include "daemon.hpp"

#include <chrono>
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
#include "pbms/mpi/mpmd.hpp"
#include "pbms/progress_meter.hpp"
#include "run_record.hpp"

namespace pbms::coupler {
namespace {

using Clock = std::chrono::steady_clock;

struct DriverLink {
  mpi::App app;
  mpi::Channel channel;
  protocol::Hello hello;
};

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

YAML::Node resolve_references(const YAML::Node& node,
                              const std::map<std::string, StageResults>& done) {
  if (node.IsMap() && node.size() == 1 && node["from"] && node["from"].IsScalar()) {
    const std::string target = node["from"].Scalar();
    const auto dot = target.find('.');
    const std::string stage = target.substr(0, dot), key = target.substr(dot + 1);
    const auto it = done.find(stage);
    const auto v = it == done.end() ? std::nullopt : it->second.scalar(key);
    if (!v) throw Error(fmt::format("stage '{}' did not produce '{}'", stage, key));
    return YAML::Node(*v);
  }
  if (node.IsMap()) {
    YAML::Node out(YAML::NodeType::Map);
    for (const auto& kv : node) out[kv.first] = resolve_references(kv.second, done);
    return out;
  }
  if (node.IsSequence()) {
    YAML::Node out(YAML::NodeType::Sequence);
    for (const auto& e : node) out.push_back(resolve_references(e, done));
    return out;
  }
  return node;
}

std::string dump(const YAML::Node& n) {
  YAML::Emitter e;
  e.SetDoublePrecision(17);
  e << n;
  return e.c_str();
}

class Daemon {
 public:
  explicit Daemon(const DaemonOptions& opt) : opt_(opt), console_(opt.terminal) {}

  int run() {
    auto world = mpi::MpmdWorld::join(mpi::Role::kCoupler);
    if (world.local().size() != 1) throw Error("the coupler runs as exactly one process");
    for (const auto& app : world.drivers()) {
      links_.push_back({app, mpi::Channel(world.connect(app)), {}});
    }
    for (auto& l : links_) {
      auto m = l.channel.receive();
      auto* h = std::get_if<protocol::Hello>(&m);
      if (!h) throw Error("a driver opened with something other than Hello");
      l.hello = *h;
    }

    // The launcher validated the workflow, but the daemon checks again: it
    // must never act on a config it has not read itself.
    const auto drivers = discover_drivers(opt_.drivers_dir);
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
      for (const auto& l : links_) {
        hellos.push_back(l.hello);
        sizes.push_back(l.app.size);
      }
      for (auto& p : check_capabilities(loaded.workflow->stages, hellos, sizes)) {
        problems.push_back(std::move(p));
      }
    }
    if (!problems.empty()) {
      for (const auto& p : problems) std::cerr << "pbms: refused: " << p << "\n";
      welcome_all(false, fmt::format("{}", fmt::join(problems, "; ")));
      return 1;
    }
    wf_ = std::move(*loaded.workflow);

    std::vector<ProgramLayout> layout{{"coupler", 1, world.coupler().first_world_rank}};
    for (const auto& l : links_) {
      layout.push_back({l.hello.program, l.app.size, l.app.first_world_rank});
    }
    record_ = std::make_unique<RunRecord>(wf_, layout, opt_.command_line);
    for (const auto& l : links_) record_->set_software(l.hello.software);
    setup_log();
    welcome_all(true, "");

    log(fmt::format("run '{}' -> {}", wf_.run_name, record_->dir().string()));
    for (const auto& l : links_) {
      log(fmt::format("  {} on {} rank{} (declares: {})", l.hello.program, l.app.size,
                      l.app.size == 1 ? "" : "s", fmt::join(l.hello.capabilities, ", ")));
    }
    for (size_t i = 0; i < wf_.stages.size(); ++i) {
      try {
        run_stage(i);
      } catch (const std::exception& e) {
        fail("coupler", 0, wf_.stages[i].name, -1, e.what());
      }
    }
    for (const auto& l : links_) l.channel.send(protocol::Shutdown{"workflow complete"}, 0);
    record_->finished();
    log(fmt::format("done: summary in {}", (record_->dir() / "summary.yaml").string()));
    spdlog::shutdown();
    return 0;
  }

 private:
  void welcome_all(bool accepted, const std::string& reason) {
    for (const auto& l : links_) {
      protocol::Welcome w;
      w.accepted = accepted;
      w.reason = reason;
      for (const auto& o : links_) {
        if (o.app.appnum != l.app.appnum)
          w.peers.push_back({o.hello.program, o.app.appnum, o.app.size});
      }
      l.channel.send(w, 0);
    }
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

  const DriverLink& link_for(const std::string& program) const {
    for (const auto& l : links_) {
      if (l.hello.program == program) return l;
    }
    throw Error(fmt::format("{} is not part of this job", program));
  }

  void run_stage(size_t index) {
    const auto& stage = wf_.stages[index];
    const auto& link = link_for(stage.program);
    protocol::RunStage rs;
    rs.index = static_cast<int32_t>(index);
    rs.name = stage.name;
    rs.kind = stage.kind;
    try {
      rs.params_yaml = dump(resolve_references(stage.params, done_));
    } catch (const Error& e) {
      fail(stage.program, 0, stage.name, -1, e.what());
    }
    rs.materials_yaml = dump(wf_.materials);
    rs.run_dir = record_->dir().string();
    rs.seed = wf_.seed;
    record_->stage_started(stage);
    log(fmt::format("stage {}/{} '{}' ({}) on {}", index + 1, wf_.stages.size(), stage.name,
                    stage.kind, stage.program));
    link.channel.send(rs, 0);

    ProgressMeter meter(stage.name, opt_.terminal);
    ProgressMeter file_meter(stage.name, false);
    const auto t0 = Clock::now();
    auto now = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
    auto pause = std::chrono::microseconds(100);
    for (;;) {
      bool got = false;
      for (const auto& l : links_) {
        int source = 0;
        auto m = l.channel.poll(&source);
        if (!m) continue;
        got = true;
        if (auto* p = std::get_if<protocol::Progress>(&*m)) {
          record_->progress(p->stage, p->step, p->total_steps, p->sim_time_ps);
          if (auto line = meter.update(p->step, p->total_steps, p->sim_time_ps, p->phase, now())) {
            console_.progress(*line);
          }
          if (auto line =
                  file_meter.update(p->step, p->total_steps, p->sim_time_ps, p->phase, now())) {
            if (file_log_) file_log_->info(*line);
          }
        } else if (auto* d = std::get_if<protocol::StageDone>(&*m)) {
          console_.end_progress();
          record_->stage_finished(stage, d->results, d->wall_s);
          log(fmt::format("stage '{}' finished in {}", stage.name, format_duration(d->wall_s)));
          for (const auto& s : d->results.scalars) {
            const std::string err =
                std::isfinite(s.std_error) ? fmt::format(" ± {:.4g}", s.std_error) : "";
            log(fmt::format("  {} = {:.6g}{} {}", s.key, s.value, err, s.unit));
          }
          done_[stage.name] = std::move(d->results);
          return;
        } else if (auto* f = std::get_if<protocol::Fatal>(&*m)) {
          fail(f->program, f->rank, f->stage, f->step, f->message);
        } else {
          fail(l.hello.program, source, stage.name, -1,
               fmt::format(
                   "protocol error: unexpected {} message",
                   std::visit([](const auto& x) { return protocol::type_name(x.kType); }, *m)));
        }
      }
      if (got) {
        pause = std::chrono::microseconds(100);
      } else {
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(20000));
      }
    }
  }

  [[noreturn]] void fail(const std::string& program, int rank, const std::string& stage,
                         int64_t step, const std::string& message) {
    console_.end_progress();
    const std::string where = stage.empty()
                                  ? std::string()
                                  : fmt::format(" in stage '{}'{}", stage,
                                                step >= 0 ? fmt::format(" at step {}", step) : "");
    const std::string text = fmt::format("{} rank {} failed{}: {}", program, rank, where, message);
    std::cerr << "pbms: error: " << text << "\n" << std::flush;
    if (file_log_) file_log_->error(text);
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
  std::vector<DriverLink> links_;
  config::Workflow wf_;
  std::unique_ptr<RunRecord> record_;
  std::shared_ptr<spdlog::logger> file_log_;
  std::map<std::string, StageResults> done_;
};

}  // namespace

int run_daemon(const DaemonOptions& opt) {
  Daemon d(opt);
  return d.run();
}

}  // namespace pbms::coupler
