// md_tension's checkpoints: LAMMPS' own restart file of the system (atoms,
// box, groups, the thermostat's and barostat's variables) and the script so
// far, with what LAMMPS' fixes hold that a restart file does not carry: the
// stress samples taken so far (fix vector) and the grips. Written at chunk
// boundaries that fall on sample boundaries, so no sampling window is cut.
//
// A stage that has written a checkpoint goes on from it exactly as a
// resumed stage does: a new LAMMPS instance reads the restart file back
// (ContinueFromCheckpoint). A restart file does not hold all that a running
// LAMMPS holds (the order of the neighbour lists' pairs, for one), and a
// stage that went on in its own instance would part from a resumed one by
// round-off that MD then grows; this way the two take the same steps.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lammps.hpp"
#include "md_setup.hpp"
#include "pbms/driver/stage_checkpoints.hpp"

namespace pbms::md {

// Where the stage stands at a checkpoint, beside the LAMMPS system.
struct TensionState {
  bool loading = false;                      // else equilibrating
  int64_t step = 0;                          // LAMMPS' step within the phase
  std::vector<std::vector<double>> samples;  // fix vector rows, loading only
  std::vector<double> grips;                 // a nanowire's, once loading
};

// Thrown after a checkpoint was written: the stage goes on from `file`.
struct ContinueFromCheckpoint {
  std::filesystem::path file;
};

class TensionCheckpoints {
 public:
  // `sample_width`: values per fix vector row; `from`: the checkpoint the
  // stage goes on from (none: it starts).
  TensionCheckpoints(StageContext& ctx, StageCheckpoints& checkpoints, Lammps& lmp,
                     int sample_width, const CheckpointArchive* from);

  // Collective: on a stage that goes on from a checkpoint, reads its
  // restart file into the (new) LAMMPS instance, with the material's pair
  // style, which a restart file does not hold, and returns where the stage
  // stands.
  std::optional<TensionState> resume(const MdMaterial& mat);
  [[nodiscard]] const std::optional<TensionState>& resumed() const { return resumed_; }
  // Whether the stage goes on inside this phase of the resumed run.
  [[nodiscard]] bool resumes_in(bool loading) const {
    return resumed_ && resumed_->loading == loading;
  }

  // Called after each chunk of a phase (collective): writes a checkpoint
  // when one is due or a stop was asked for, then ends a stopped stage
  // (StageFailure) or goes on from the checkpoint (ContinueFromCheckpoint).
  // `step` is the phase's, `stage_step` the stage's of `total`.
  void after_chunk(bool loading, int64_t step, int64_t stage_step, int64_t total, double dt);
  // Before the first chunk of a resumed phase: the script becomes the run's
  // that wrote the checkpoint, so that tension.in replays the whole stage.
  void adopt_script();

  void set_grips(std::vector<double> grips) { grips_ = std::move(grips); }
  // The stress samples of the loading, resumed ones first.
  [[nodiscard]] std::vector<std::vector<double>> samples() const;

 private:
  [[nodiscard]] CheckpointArchive archive(bool loading, int64_t step, int64_t stage_step);

  StageContext& ctx_;
  Lammps& lmp_;
  int width_;
  StageCheckpoints& checkpoints_;
  const CheckpointArchive* from_;
  std::optional<TensionState> resumed_;
  std::vector<std::string> earlier_script_;
  std::vector<double> grips_;
  std::vector<std::vector<double>> kept_;  // samples up to the checkpoint gone on from
  int64_t previous_ = 0;                   // the stage step of the previous chunk boundary
};

}  // namespace pbms::md
