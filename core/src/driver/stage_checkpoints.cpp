#include "pbms/driver/stage_checkpoints.hpp"

#include <fmt/format.h>

#include "pbms/io/yaml_file.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/version.hpp"

namespace pbms {
namespace {

// FNV-1a: a digest to tell configs apart, not a guard against tampering.
std::uint64_t digest(const std::string& text) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

}  // namespace

StageCheckpoints::StageCheckpoints(StageContext& ctx) : ctx_(ctx) {
  if (enabled()) window_.emplace();
}

void StageCheckpoints::run_as_part(std::string part, std::function<bool(bool)> any_part) {
  part_ = std::move(part);
  any_part_ = std::move(any_part);
}

std::string StageCheckpoints::write(std::int64_t step, double sim_time_ps,
                                    const std::function<CheckpointArchive()>& make) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string file = write(step, sim_time_ps, make());
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++written_;
  return file;
}

void StageCheckpoints::report(StageResults& r) const {
  if (written_ == 0) return;
  const std::string prefix = part_.empty() ? std::string() : part_ + "_";
  r.attributes[prefix + "checkpoints_written"] = fmt::format("{}", written_);
  r.attributes[prefix + "checkpoint_seconds"] = fmt::format("{:.6g}", seconds_);
}

bool StageCheckpoints::stop_agreed(std::int64_t step) {
  if (step % kStopCheckEvery != 0) return false;
  return stop_now();
}

bool StageCheckpoints::stop_now() {
  if (!enabled()) return false;
  int mine = stop_requested() ? 1 : 0, any = 0;
  mpi::check(MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, ctx_.comm()), "MPI_Allreduce");
  return any_part_ ? any_part_(any != 0) : any != 0;
}

std::string StageCheckpoints::stopped_message(std::int64_t step, std::int64_t total,
                                              const std::string& file) {
  return fmt::format(
      "{} (SIGTERM or SIGUSR1: a wall-time limit?) after step {} of {}; the "
      "checkpoint {} holds the run",
      kStoppedBySignal, step, total, file);
}

std::string StageCheckpoints::identity() const {
  std::string text = yaml_text(ctx_.params());
  if (ctx_.params()["material"]) text += yaml_text(ctx_.material());
  return fmt::format("stage '{}' ({}), parameters {:016x}; PBMS {} ({})", ctx_.stage(), ctx_.kind(),
                     digest(text), version(), git_hash());
}

CheckpointArchive StageCheckpoints::resume_archive() const {
  return CheckpointArchive::read(ctx_.checkpoint_plan().resume_from, identity(), ctx_.comm());
}

bool StageCheckpoints::due_after(std::int64_t previous, std::int64_t step, std::int64_t total) {
  const CheckpointPlan& plan = ctx_.checkpoint_plan();
  if (!plan.enabled() || step >= total) return false;
  if (plan.every_steps > 0 && step / plan.every_steps > previous / plan.every_steps) return true;
  if (!(plan.every_seconds > 0.0)) return false;
  // Clocks differ between ranks and programs: rank 0's decides for its
  // program, and any program's for all.
  int yes = 0;
  if (ctx_.rank() == 0) {
    yes = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() >=
          plan.every_seconds;
  }
  mpi::check(MPI_Bcast(&yes, 1, MPI_INT, 0, ctx_.comm()), "MPI_Bcast");
  return any_part_ ? any_part_(yes != 0) : yes != 0;
}

std::string StageCheckpoints::write(std::int64_t step, double sim_time_ps,
                                    const CheckpointArchive& archive) {
  const auto file = [&](const std::string& part) {
    return fmt::format("{}/checkpoints/step_{:012d}{}.h5", ctx_.stage(), step,
                       part.empty() ? std::string() : "." + part);
  };
  archive.write(ctx_.run_dir() / file(part_), identity(), ctx_.comm());
  if (ctx_.rank() == 0) ctx_.checkpoint_written(step, sim_time_ps, file(part_));
  mpi::check(MPI_Barrier(ctx_.comm()), "MPI_Barrier");
  last_ = std::chrono::steady_clock::now();
  return file("");
}

}  // namespace pbms
