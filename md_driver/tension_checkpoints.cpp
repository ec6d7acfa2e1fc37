#include "tension_checkpoints.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::md {
namespace {

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<double> flat(const std::vector<std::vector<double>>& rows) {
  std::vector<double> out;
  for (const auto& r : rows) out.insert(out.end(), r.begin(), r.end());
  return out;
}

std::vector<std::vector<double>> rows_of(const std::vector<double>& values, int width) {
  std::vector<std::vector<double>> out;
  for (std::size_t k = 0; k + static_cast<std::size_t>(width) <= values.size();
       k += static_cast<std::size_t>(width)) {
    out.emplace_back(values.begin() + static_cast<std::ptrdiff_t>(k),
                     values.begin() + static_cast<std::ptrdiff_t>(k) + width);
  }
  return out;
}

}  // namespace

TensionCheckpoints::TensionCheckpoints(StageContext& ctx, StageCheckpoints& checkpoints,
                                       Lammps& lmp, int sample_width, const CheckpointArchive* from)
    : ctx_(ctx), lmp_(lmp), width_(sample_width), checkpoints_(checkpoints), from_(from) {}

std::optional<TensionState> TensionCheckpoints::resume(const MdMaterial& mat) {
  if (!from_) return std::nullopt;
  const CheckpointArchive& a = *from_;
  // LAMMPS reads its restart file itself, on every rank: rank 0 puts it
  // beside the checkpoint for as long as that takes.
  const auto restart = ctx_.stage_dir() / "checkpoints" / "resume.lammps.restart";
  if (ctx_.rank() == 0) {
    std::ofstream(restart, std::ios::binary) << a.bytes("lammps/restart");
  }
  mpi::check(MPI_Barrier(ctx_.comm()), "MPI_Barrier");
  lmp_.read_restart(restart);
  mpi::check(MPI_Barrier(ctx_.comm()), "MPI_Barrier");
  if (ctx_.rank() == 0) std::filesystem::remove(restart);
  set_pair_style(lmp_, mat);

  TensionState s;
  s.loading = a.scalar("tension/loading") != 0.0;
  s.step = static_cast<int64_t>(a.scalar("tension/step"));
  s.samples = rows_of(a.get("tension/samples"), width_);
  if (s.loading) kept_ = s.samples;
  s.grips = a.get("tension/grips");
  grips_ = s.grips;
  earlier_script_ = lines_of(a.bytes("lammps/script"));
  previous_ = static_cast<int64_t>(a.scalar("tension/stage_step"));
  resumed_ = s;
  return resumed_;
}

void TensionCheckpoints::adopt_script() {
  if (earlier_script_.empty()) return;
  lmp_.adopt_script(std::move(earlier_script_));
  lmp_.comment("resumed here from the checkpoint above; the commands that read it are not shown");
  earlier_script_.clear();
}

std::vector<std::vector<double>> TensionCheckpoints::samples() const {
  std::vector<std::vector<double>> rows = kept_;
  auto now = lmp_.fix_array("samples", width_);
  // The first row of a fix vector made at a checkpoint is the checkpoint's
  // step again, where the kept samples end.
  const std::size_t skip = resumes_in(true) && !now.empty() ? 1 : 0;
  rows.insert(rows.end(), now.begin() + static_cast<std::ptrdiff_t>(skip), now.end());
  return rows;
}

CheckpointArchive TensionCheckpoints::archive(bool loading, int64_t step, int64_t stage_step) {
  CheckpointArchive a;
  // Before write_restart, which deletes the fix vector (Lammps::write_restart).
  a.put("tension/samples", loading ? flat(samples()) : std::vector<double>{});
  const auto restart = ctx_.stage_dir() / "checkpoints" / "write.lammps.restart";
  if (ctx_.rank() == 0) std::filesystem::create_directories(restart.parent_path());
  mpi::check(MPI_Barrier(ctx_.comm()), "MPI_Barrier");
  lmp_.write_restart(restart,
                     loading ? std::vector<std::string>{"samples"} : std::vector<std::string>{});
  if (ctx_.rank() == 0) {
    a.put_bytes("lammps/restart", file_bytes(restart));
    std::filesystem::remove(restart);
  }
  a.put_bytes("lammps/script", joined(lmp_.script()));
  a.put("tension/loading", loading ? 1.0 : 0.0);
  a.put("tension/step", static_cast<double>(step));
  a.put("tension/stage_step", static_cast<double>(stage_step));
  a.put("tension/grips", grips_);
  return a;
}

void TensionCheckpoints::after_chunk(bool loading, int64_t step, int64_t stage_step, int64_t total,
                                     double dt) {
  if (!checkpoints_.enabled()) return;
  const int64_t previous = previous_;
  previous_ = stage_step;
  const bool stop = stage_step < total && checkpoints_.stop_now();
  if (!stop && !checkpoints_.due_after(previous, stage_step, total)) return;
  const std::string file = checkpoints_.write(stage_step, static_cast<double>(stage_step) * dt,
                                              [&] { return archive(loading, step, stage_step); });
  if (stop) throw StageFailure(StageCheckpoints::stopped_message(stage_step, total, file));
  throw ContinueFromCheckpoint{ctx_.run_dir() / file};
}

}  // namespace pbms::md
