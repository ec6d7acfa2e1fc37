#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <thread>

#include <fmt/format.h>

#include "pbms/driver/stage_kind.hpp"
#include "pbms/driver/stop_request.hpp"
#include "pbms/error.hpp"
#include "pbms/mpi/mpmd.hpp"

namespace pbms {
namespace {

using Clock = std::chrono::steady_clock;

// Where this rank is, for failure messages. Plain arrays so the crash signal
// handler can read them without allocating.
char g_program[64] = "driver";
char g_stage[128] = "";
int g_rank = 0;
std::atomic<int64_t> g_step{-1};

void append(char* buf, size_t cap, size_t& len, const char* s) {
  while (*s && len + 1 < cap) buf[len++] = *s++;
}
void append_int(char* buf, size_t cap, size_t& len, long long v) {
  char digits[24];
  int n = 0;
  const bool neg = v < 0;
  unsigned long long u =
      neg ? static_cast<unsigned long long>(-v) : static_cast<unsigned long long>(v);
  do {
    digits[n++] = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u && n < 23);
  if (neg) append(buf, cap, len, "-");
  while (n) {
    const char c[2] = {digits[--n], 0};
    append(buf, cap, len, c);
  }
}

extern "C" void on_crash_signal(int sig) {
  char buf[512];
  size_t len = 0;
  append(buf, sizeof buf, len, "pbms: ");
  append(buf, sizeof buf, len, g_program);
  append(buf, sizeof buf, len, " rank ");
  append_int(buf, sizeof buf, len, g_rank);
  append(buf, sizeof buf, len, " died of signal ");
  append_int(buf, sizeof buf, len, sig);
  append(buf, sizeof buf, len, " (");
  append(buf, sizeof buf, len, strsignal(sig));
  append(buf, sizeof buf, len, ")");
  if (g_stage[0]) {
    append(buf, sizeof buf, len, " in stage '");
    append(buf, sizeof buf, len, g_stage);
    append(buf, sizeof buf, len, "' at step ");
    append_int(buf, sizeof buf, len, g_step.load());
  }
  append(buf, sizeof buf, len, "\n");
  [[maybe_unused]] auto w = write(STDERR_FILENO, buf, len);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void copy_name(char* dst, size_t cap, const std::string& s) {
  std::snprintf(dst, cap, "%s", s.c_str());
}

// This process's CPU time so far (user and system, s) and its peak resident
// memory (MB).
struct ProcessUsage {
  double cpu_s = 0.0;
  double peak_rss_mb = 0.0;
};
ProcessUsage process_usage() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return {seconds(u.ru_utime) + seconds(u.ru_stime), static_cast<double>(u.ru_maxrss) / 1024.0};
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

void set_current_step(int64_t step) {
  g_step.store(step);
}

class DriverRuntime;
namespace {
DriverRuntime* g_runtime = nullptr;
std::string (*g_finalize_describe)() = nullptr;
}  // namespace

void set_unexpected_finalize_handler(std::string (*describe)()) {
  g_finalize_describe = describe;
}

std::string describe_unexpected_finalize() {
  std::string text = g_finalize_describe ? g_finalize_describe() : std::string();
  return text.empty() ? "a library called MPI_Finalize in the middle of the run" : text;
}

class DriverRuntime {
 public:
  DriverRuntime(const DriverInfo& info, const StageRegistry& registry)
      : info_(info), registry_(registry), world_(mpi::MpmdWorld::join(mpi::Role::kDriver)) {
    g_rank = world_.local().rank();
    coupler_ = mpi::Channel(world_.connect(world_.coupler()));
    const auto drivers = world_.drivers();
    for (size_t i = 0; i < drivers.size(); ++i) {
      for (size_t j = i + 1; j < drivers.size(); ++j) {
        if (drivers[i].appnum == world_.appnum()) {
          peers_by_app_[drivers[j].appnum] = world_.connect(drivers[j]);
        } else if (drivers[j].appnum == world_.appnum()) {
          peers_by_app_[drivers[i].appnum] = world_.connect(drivers[i]);
        }
      }
    }
  }

  // Each rank group serves its own stream of requests; its leader talks to
  // the coupler. Until the coupler sends Regroup the group is the program.
  int serve() {
    if (!handshake()) return 1;
    regroup(local().size());
    for (;;) {
      protocol::Message m = next_command();
      if (std::holds_alternative<protocol::Shutdown>(m)) return 0;
      if (const auto* rs = std::get_if<protocol::RunStage>(&m)) {
        run_stage(*rs);
      } else if (const auto* rg = std::get_if<protocol::Regroup>(&m)) {
        regroup(rg->group_ranks);
      } else {
        throw Error("unexpected message from the coupler");
      }
    }
  }

  [[noreturn]] void fail(const std::string& message) {
    protocol::Fatal f;
    f.program = info_.program;
    f.rank = world_.local().rank();
    f.stage = g_stage;
    f.step = g_step.load();
    f.message = message;
    std::cerr << fmt::format("pbms: {} rank {} failed{}: {}\n", f.program, f.rank,
                             f.stage.empty()
                                 ? std::string()
                                 : fmt::format(" in stage '{}' at step {}", f.stage, f.step),
                             message)
              << std::flush;
    try {
      coupler_.send(f, 0);
    } catch (...) {
    }
    // The coupler records the failure and aborts the whole job; give it time,
    // then take the job down ourselves in case the coupler is gone too.
    std::this_thread::sleep_for(std::chrono::seconds(5));
    MPI_Abort(MPI_COMM_WORLD, 1);
    std::_Exit(1);
  }

  const mpi::Comm& local() const { return world_.local(); }
  const mpi::Comm& group() const { return group_; }
  const mpi::Channel& coupler() const { return coupler_; }
  MPI_Comm peer(const std::string& program) const {
    for (const auto& p : peer_programs_) {
      if (p.program == program) {
        auto it = peers_by_app_.find(p.app);
        if (it != peers_by_app_.end()) return it->second.get();
      }
    }
    return MPI_COMM_NULL;
  }

 private:
  bool handshake() {
    int accepted = 0;
    if (local().rank() == 0) {
      protocol::Hello h;
      h.program = info_.program;
      h.short_name = info_.short_name;
      h.ranks = local().size();
      for (const auto& s : registry_.specs()) h.capabilities.push_back(s.kind);
      for (const auto& [k, v] : info_.software) h.software.push_back(k + "=" + v);
      coupler_.send(h, 0);
      auto reply = coupler_.receive();
      const auto* w = std::get_if<protocol::Welcome>(&reply);
      if (!w) throw Error("the coupler answered the handshake with something other than Welcome");
      accepted = w->accepted ? 1 : 0;
      if (!w->accepted) {
        std::cerr << fmt::format("pbms: {} was refused by the coupler: {}\n", info_.program,
                                 w->reason);
      }
      welcome_bytes_ = protocol::pack(*w);
    }
    mpi::bcast_gently(&accepted, 1, MPI_INT, 0, local().get());
    if (!accepted) return false;
    const auto m = broadcast(welcome_bytes_, local().get());
    peer_programs_ = std::get<protocol::Welcome>(m).peers;
    return true;
  }

  // Every rank of the program arrives here: the coupler sends Regroup to
  // every group leader. Group g holds ranks [g n, (g + 1) n).
  void regroup(int group_ranks) {
    const int n = std::max(1, group_ranks);
    MPI_Request barrier = MPI_REQUEST_NULL;
    mpi::check(MPI_Ibarrier(local().get(), &barrier), "MPI_Ibarrier");
    mpi::wait_gently(barrier);
    MPI_Comm split = MPI_COMM_NULL;
    mpi::check(MPI_Comm_split(local().get(), local().rank() / n, local().rank(), &split),
               "MPI_Comm_split");
    group_ = mpi::Comm(split);
  }

  // The root holds the bytes; every rank of `comm` gets the decoded message.
  static protocol::Message broadcast(std::vector<std::byte>& bytes, MPI_Comm comm) {
    uint64_t n = bytes.size();
    mpi::bcast_gently(&n, 1, MPI_UINT64_T, 0, comm);
    bytes.resize(n);
    mpi::bcast_gently(bytes.data(), static_cast<int>(n), MPI_BYTE, 0, comm);
    return protocol::unpack(bytes.data(), bytes.size());
  }

  protocol::Message next_command() {
    std::vector<std::byte> bytes;
    if (group().rank() == 0) bytes = protocol::pack(coupler_.receive());
    return broadcast(bytes, group().get());
  }

  void run_stage(const protocol::RunStage& rs) {
    copy_name(g_stage, sizeof g_stage, rs.name);
    g_step.store(0);
    const auto t0 = Clock::now();
    try {
      StageContext ctx(*this, rs.request, rs.name, rs.kind, YAML::Load(rs.params_yaml),
                       YAML::Load(rs.materials_yaml), rs.run_dir, rs.seed);
      CheckpointPlan plan = CheckpointPlan::from_yaml(YAML::Load(rs.checkpoint_yaml));
      plan.resume_from = rs.resume_from;
      ctx.set_checkpoint_plan(std::move(plan));
      auto stage = registry_.create(rs.kind);
      const ProcessUsage before = process_usage();
      stage->run(ctx);
      record_usage(ctx.results(), before);
      if (group().rank() == 0) {
        protocol::StageDone done;
        done.request = rs.request;
        done.stage = rs.name;
        done.wall_s = seconds_since(t0);
        done.results = std::move(ctx.results());
        coupler_.send(done, 0);
      }
    } catch (const StageFailure& e) {
      if (group().rank() == 0) {
        protocol::StageFailed failed;
        failed.request = rs.request;
        failed.stage = rs.name;
        failed.program = info_.program;
        failed.rank = local().rank();
        failed.step = g_step.load();
        failed.wall_s = seconds_since(t0);
        failed.reason = e.what();
        coupler_.send(failed, 0);
      }
    }
    g_stage[0] = 0;
    g_step.store(-1);
  }

  // The program's CPU time over the stage, summed over its ranks, and the
  // largest peak memory of any of its ranks, as attributes of the stage's
  // results (cpu_s.<program>, peak_rss_mb.<program>): what a cost table
  // needs, kept out of the summary's scalars, which a resumed run must give
  // bit for bit. Collective over the program's ranks.
  void record_usage(StageResults& r, const ProcessUsage& before) {
    const ProcessUsage now = process_usage();
    double cpu = now.cpu_s - before.cpu_s, rss = now.peak_rss_mb;
    MPI_Allreduce(MPI_IN_PLACE, &cpu, 1, MPI_DOUBLE, MPI_SUM, group().get());
    MPI_Allreduce(MPI_IN_PLACE, &rss, 1, MPI_DOUBLE, MPI_MAX, group().get());
    r.attributes["cpu_s." + info_.program] = fmt::format("{:.3f}", cpu);
    r.attributes["peak_rss_mb." + info_.program] = fmt::format("{:.1f}", rss);
  }

  const DriverInfo& info_;
  const StageRegistry& registry_;
  mpi::MpmdWorld world_;
  mpi::Comm group_;
  mpi::Channel coupler_;
  std::map<int, mpi::Comm> peers_by_app_;
  std::vector<protocol::Peer> peer_programs_;
  std::vector<std::byte> welcome_bytes_;
};

// ---------------------------------------------------------------- context

StageContext::StageContext(DriverRuntime& runtime, int64_t request, std::string stage,
                           std::string kind, const YAML::Node& params, const YAML::Node& materials,
                           std::filesystem::path run_dir, uint64_t seed)
    : runtime_(runtime),
      request_(request),
      stage_(std::move(stage)),
      kind_(std::move(kind)),
      params_(params),
      materials_(materials),
      run_dir_(std::move(run_dir)),
      seed_(seed) {}

YAML::Node StageContext::material(const std::string& name) const {
  const YAML::Node m = materials_[name];
  if (!m) throw Error(fmt::format("material '{}' is not defined", name));
  return m;
}

YAML::Node StageContext::material() const {
  return material(params_["material"].as<std::string>());
}

MPI_Comm StageContext::comm() const {
  return runtime_.group().get();
}
int StageContext::rank() const {
  return runtime_.group().rank();
}
int StageContext::size() const {
  return runtime_.group().size();
}

void StageContext::fail_together(bool failed, const std::string& reason) const {
  // The lowest failing rank speaks for the group.
  const int mine = failed ? rank() : size();
  int first = size();
  MPI_Request r = MPI_REQUEST_NULL;
  mpi::check(MPI_Iallreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm(), &r), "MPI_Iallreduce");
  mpi::wait_gently(r);
  if (first == size()) return;
  std::string text = reason;
  int length = static_cast<int>(text.size());
  mpi::bcast_gently(&length, 1, MPI_INT, first, comm());
  text.resize(static_cast<std::size_t>(length));
  mpi::bcast_gently(text.data(), length, MPI_CHAR, first, comm());
  throw StageFailure(text);
}
MPI_Comm StageContext::peer(const std::string& program) const {
  return runtime_.peer(program);
}

std::filesystem::path StageContext::stage_dir() const {
  auto d = run_dir_ / stage_;
  std::filesystem::create_directories(d);
  return d;
}

void StageContext::progress(int64_t step, int64_t total_steps, double sim_time_ps,
                            const std::string& phase) {
  set_current_step(step);
  if (rank() != 0) return;
  const double now = seconds_since(created_);
  const int64_t one_percent = std::max<int64_t>(1, total_steps / 100);
  const bool due = step >= total_steps || last_report_step_ < 0 ||
                   step - last_report_step_ >= one_percent || now - last_report_s_ >= 0.5;
  if (!due) return;
  last_report_s_ = now;
  last_report_step_ = step;
  protocol::Progress p;
  p.request = request_;
  p.stage = stage_;
  p.step = step;
  p.total_steps = total_steps;
  p.sim_time_ps = sim_time_ps;
  p.phase = phase;
  runtime_.coupler().send(p, 0);
}

void StageContext::checkpoint_written(int64_t step, double sim_time_ps, const std::string& file) {
  if (rank() != 0) return;
  protocol::Progress p;
  p.request = request_;
  p.stage = stage_;
  p.step = step;
  p.sim_time_ps = sim_time_ps;
  p.phase = "checkpoint";
  p.checkpoint = file;
  runtime_.coupler().send(p, 0);
}

// ---------------------------------------------------------------- registry

void StageRegistry::add(config::StageKindSpec spec, Factory factory) {
  const auto kind = spec.kind;
  entries_[kind] = {std::move(spec), std::move(factory)};
}

std::unique_ptr<StageKind> StageRegistry::create(const std::string& kind) const {
  auto it = entries_.find(kind);
  if (it == entries_.end()) throw Error(fmt::format("this driver has no stage kind '{}'", kind));
  return it->second.second();
}

std::vector<config::StageKindSpec> StageRegistry::specs() const {
  std::vector<config::StageKindSpec> out;
  for (const auto& [k, e] : entries_) out.push_back(e.first);
  return out;
}

// ---------------------------------------------------------------- main

void abort_job(const std::string& message) {
  if (g_runtime) g_runtime->fail(message);
  std::cerr << fmt::format("pbms: {} rank {}: {}\n", g_program, g_rank, message) << std::flush;
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::_Exit(1);
}

int run_driver(int argc, char** argv, const DriverInfo& info, const StageRegistry& registry) {
  copy_name(g_program, sizeof g_program, info.program);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--describe") {
      config::DriverDescription d;
      d.program = info.program;
      d.short_name = info.short_name;
      d.protocol_version = protocol::kProtocolVersion;
      d.software = info.software;
      d.stage_kinds = registry.specs();
      d.material_kinds = registry.materials();
      YAML::Emitter out;
      out << to_yaml(d);
      std::cout << out.c_str() << "\n";
      return 0;
    }
    if (a == "--help" || a == "-h") {
      std::cout << fmt::format(
          "{0}: a PBMS driver. It is started by `./pbms run`, inside one MPMD MPI job with the\n"
          "coupler, and runs the stages the coupler sends it.\n\n"
          "Usage:\n  {0} --describe   print the stage kinds it runs and their parameters (YAML)\n"
          "  {0} --help       this text\n\nStage kinds:\n",
          info.program);
      for (const auto& s : registry.specs())
        std::cout << fmt::format("  {:16} {}\n", s.kind, s.doc);
      if (!registry.materials().empty()) std::cout << "\nMaterial kinds:\n";
      for (const auto& m : registry.materials())
        std::cout << fmt::format("  {:16} {}\n", m.kind, m.doc);
      return 0;
    }
  }
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, on_crash_signal);
  install_stop_handlers();

  mpi::Environment env(argc, argv);
  std::unique_ptr<DriverRuntime> runtime;
  try {
    runtime = std::make_unique<DriverRuntime>(info, registry);
  } catch (const std::exception& e) {
    std::cerr << fmt::format("pbms: {} could not join the job: {}\n", info.program, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }
  g_runtime = runtime.get();
  try {
    return runtime->serve();
  } catch (const std::exception& e) {
    runtime->fail(e.what());
  }
}

}  // namespace pbms
