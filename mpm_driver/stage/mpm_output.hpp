// What an mpm_run writes while it runs: H5MD particle frames and XDMF grid
// frames (nodal mass and velocity), each every so many steps.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/mpm_engine.hpp"
#include "mpm_run_params.hpp"
#include "pbms/grid/grid_field_writer.hpp"
#include "pbms/io/h5md_writer.hpp"

namespace pbms::mpm {

class MpmOutput {
 public:
  // Files go to `stage_dir`; `stage` names it in files().
  // A run that will resume() creates no file: it goes on with those it has.
  MpmOutput(const MpmEngine& engine, const MpmRunParams& params,
            const std::filesystem::path& stage_dir, const std::string& stage,
            bool resuming = false);

  // Collective, for a run resumed from a checkpoint after `last_step`:
  // goes on with the particle and grid files the interrupted run wrote,
  // their later frames dropped (H5mdWriter::reopen, GridFieldWriter::reopen).
  void resume(const MpmEngine& engine, std::int64_t last_step);
  // The frames due at this step. Collective.
  void write(const MpmEngine& engine, std::int64_t step, double t);
  // The files written, relative to the run directory.
  [[nodiscard]] std::vector<std::string> files() const;

 private:
  void write_particles(const MpmEngine& engine, std::int64_t step, double t);
  void write_grid(const MpmEngine& engine, std::int64_t step, double t);

  MpmRunParams params_;
  std::string stage_;
  std::array<double, 3> edges_{};
  H5mdWriter::Options particle_options_;
  std::string grid_base_;
  std::unique_ptr<H5mdWriter> particles_;
  std::unique_ptr<GridFieldWriter> grid_;
};

}  // namespace pbms::mpm
