// The particle output of a DPD stage: H5MD frames (every rank writes the
// particles it holds, each at the row of its id, so no rank gathers them),
// and the final state every rank keeps for a later stage's
// `initial: {from_stage: ...}`.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/dpd_engine.hpp"
#include "pbms/io/h5md_writer.hpp"

namespace pbms::dpd {

class DpdTrajectory {
 public:
  DpdTrajectory(MPI_Comm comm, std::filesystem::path file, bool forces, bool internal_energy);

  // Collective, for a run resumed from a checkpoint after `last_step`:
  // goes on with the file the interrupted run wrote, its later frames
  // dropped (H5mdWriter::reopen).
  void resume(const DpdEngine& engine, std::int64_t last_step);
  // Collective: one frame; the first creates the file.
  void write_frame(const DpdEngine& engine, std::int64_t step, double dt);
  // Collective: every rank keeps the whole state, sorted by id.
  void keep_final_state(const DpdEngine& engine, const std::string& stage) const;
  [[nodiscard]] bool written() const { return h5md_ != nullptr; }

 private:
  // id, type, x, v, then f and u when written: this rank's rows.
  [[nodiscard]] std::vector<double> local_rows(const DpdEngine& engine) const;
  [[nodiscard]] std::size_t width() const;
  [[nodiscard]] H5mdWriter::Options options(const DpdEngine& engine) const;

  MPI_Comm comm_;
  std::filesystem::path file_;
  bool forces_, internal_energy_;
  std::unique_ptr<H5mdWriter> h5md_;
};

}  // namespace pbms::dpd
