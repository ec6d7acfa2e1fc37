// A driver stage's checkpoints: when one is due, writing it where the
// coupler expects it (<stage>/checkpoints/step_<N>.h5), and reading the
// one a resumed run goes on from. What goes into one is the stage's own
// business (a CheckpointArchive it fills).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "pbms/driver/stage_kind.hpp"
#include "pbms/driver/stop_request.hpp"
#include "pbms/io/checkpoint_archive.hpp"

namespace pbms {

class StageCheckpoints {
 public:
  explicit StageCheckpoints(StageContext& ctx);

  // A stage that several programs run together (a concurrent stage's
  // parts) writes a file per program at steps all of them agree on.
  // `part` names this program's file, <stage>/checkpoints/step_<N>.<part>.h5
  // (empty: the main part's, step_<N>.h5); `any_part` is collective over
  // every program's ranks and says whether any program passed true. The
  // coupler records a checkpoint once every part has written its file.
  void run_as_part(std::string part, std::function<bool(bool)> any_part);

  [[nodiscard]] bool enabled() const { return ctx_.checkpoint_plan().enabled(); }
  [[nodiscard]] bool resuming() const { return !ctx_.checkpoint_plan().resume_from.empty(); }
  // Collective: the checkpoint the coupler named, read on rank 0 and handed
  // to every rank. Throws pbms::Error when it is another stage's or config's.
  [[nodiscard]] CheckpointArchive resume_archive() const;

  // Collective: whether a checkpoint is due after `step` of `total` (every
  // N steps, or every T minutes of wall time as rank 0's clock says). Never
  // after the last step: the stage's results follow at once.
  [[nodiscard]] bool due(std::int64_t step, std::int64_t total) {
    return due_after(step - 1, step, total);
  }
  // The same for a stage that can stop only every so many steps (an MD
  // run's chunks): due when a multiple of N lies in (previous, step].
  [[nodiscard]] bool due_after(std::int64_t previous, std::int64_t step, std::int64_t total);
  // Collective: every rank writes its part of `archive` (parallel HDF5),
  // then rank 0 tells the coupler. Returns the
  // checkpoint's name as the coupler records it (the main part's file),
  // relative to the run directory.
  std::string write(std::int64_t step, double sim_time_ps, const CheckpointArchive& archive);
  // write() of the archive `make` fills, timed (filling included).
  std::string write(std::int64_t step, double sim_time_ps,
                    const std::function<CheckpointArchive()>& make);
  // The attributes checkpoints_written and checkpoint_seconds (rank 0's
  // wall time in making and writing them), when any was written; a part
  // other than the main one puts its name before them (mpm_checkpoint_seconds).
  void report(StageResults& r) const;

  // Collective: whether a rank has been asked to stop (stop_request.hpp),
  // checked every kStopCheckEvery steps; never when checkpoints are off.
  [[nodiscard]] bool stop_agreed(std::int64_t step);
  static constexpr std::int64_t kStopCheckEvery = 10;
  // Collective: the same at a boundary a stage chose itself (an isotherm's
  // finished point).
  [[nodiscard]] bool stop_now();
  // The failure a stopped stage ends with: after which step, and the file.
  [[nodiscard]] static std::string stopped_message(std::int64_t step, std::int64_t total,
                                                   const std::string& file);

  // Whose state a checkpoint holds: the stage, its kind and a digest of its
  // parameters and materials; and the PBMS version and commit that wrote it
  // (a build of another commit may hold its state otherwise).
  [[nodiscard]] std::string identity() const;

 private:
  StageContext& ctx_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  std::optional<StopWindow> window_;  // open while checkpoints are on
  std::string part_;
  std::function<bool(bool)> any_part_;  // null: one program runs the stage
  int written_ = 0;
  double seconds_ = 0.0;
};

}  // namespace pbms
