// Pieces every md_driver stage shares: the material's LAMMPS commands, a
// crystal in a box, step counts, seeds and optional H5MD trajectories.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lammps.hpp"
#include "pbms/driver/stage_kind.hpp"
#include "pbms/io/h5md_writer.hpp"
#include "sutton_chen_setfl.hpp"

namespace pbms::md {

struct MdMaterial {
  std::string name;
  std::string pair_style;  // "eam/alloy"
  std::string potential;   // the setfl file (for sutton_chen, the one written)
  std::string element;
  double mass = 0.0;
  std::string lattice;  // "fcc"
  double lattice_constant = 0.0;
  std::optional<SuttonChenParameters> sutton_chen;  // a sutton_chen kind's

  // The `materials:` entry `n`, named `name`. Its kind picks the pair
  // style; a kind other than eam_alloy, eam_fs or sutton_chen is refused.
  static MdMaterial from_yaml(const std::string& name, const YAML::Node& n);
};

// The resolved `materials:` entry that a stage's `material` key names
// (collective). A sutton_chen material's table is written into the stage's
// directory first, as <name>.sutton_chen.eam.alloy.
MdMaterial material_of(const StageContext& ctx, const std::string& name);

// Commands for units, atoms, an `cells` block of `lattice` at constant `a`,
// the potential and the neighbour list. `boundary` as in LAMMPS ("p p p").
void build_crystal(Lammps& lmp, const MdMaterial& m, double a, const std::array<int, 3>& cells,
                   const std::string& boundary);
// The potential and the neighbour list alone: what a LAMMPS restart file
// does not hold of build_crystal's set-up.
void set_pair_style(Lammps& lmp, const MdMaterial& m);

int64_t steps_for(double time_ps, double timestep_ps);
// A positive 31-bit LAMMPS seed derived from the run seed and a salt.
int lammps_seed(uint64_t run_seed, uint64_t salt);
std::array<int, 3> cells_of(const YAML::Node& n);

// Writes an H5MD frame every `every` steps when the stage asks for it.
class TrajectoryRecorder {
 public:
  // `resumed_after` >= 0: a resumed stage keeps the file's frames up to
  // that step and goes on writing after them.
  TrajectoryRecorder(const StageContext& ctx, Lammps& lmp, const std::string& file, int64_t every,
                     std::array<bool, 3> periodic, int64_t resumed_after = -1);
  [[nodiscard]] bool enabled() const { return every_ > 0; }
  [[nodiscard]] int64_t every() const { return every_; }
  void maybe_write(int64_t step, double time_ps);
  [[nodiscard]] std::string relative_path() const { return relative_; }

 private:
  const StageContext& ctx_;
  Lammps& lmp_;
  int64_t every_;
  std::string relative_;
  std::vector<int64_t> ids_;  // LAMMPS' 1..N, the order lmp_.gather() returns
  std::unique_ptr<H5mdWriter> writer_;
};

// Chunk length for Lammps::run: ~1 % of the stage for progress, aligned to
// the trajectory interval so frames land on exact steps.
int64_t chunk_for(int64_t total_steps, int64_t trajectory_every);

std::vector<double> column(const std::vector<std::vector<double>>& rows, size_t j);

}  // namespace pbms::md
