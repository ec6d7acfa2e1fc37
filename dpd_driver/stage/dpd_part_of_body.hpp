// The DPD part of a concurrent stage's body, built from the stage's
// parameters on the ranks of `comm`: the body the workflow describes, split
// by the regions' solvers into the particles this part advances (DPD/MPM
// grid model, DpdGridStep) and the rows it hands to the MPM part. dpd_driver's
// concurrent stage builds it on its ranks; the monolithic reference of the
// split test (tests/tools/concurrent_monolithic.cpp) builds it on one
// process beside the MPM part, so that both run the very same set-up.
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "dpd_model.hpp"
#include "engine/concurrent_dpd_side.hpp"
#include "engine/dpd_engine.hpp"
#include "engine/dpd_grid_step.hpp"
#include "pbms/coupling/body_handover.hpp"
#include "pbms/coupling/concurrent_params.hpp"

namespace pbms::dpd {

class DpdPartOfBody {
 public:
  // `seed` is the run's; the stage mixes its name in (stage_seed).
  DpdPartOfBody(MPI_Comm comm, const YAML::Node& params, const YAML::Node& material,
                std::uint64_t seed, const std::string& stage);

  [[nodiscard]] const coupling::ConcurrentParams& params() const { return cp_; }
  // What the MPM part takes over (coupling::hand_over): its points, the
  // group names, the interface band, the partners' reach and the list skin.
  [[nodiscard]] const coupling::BodyHandover& handover() const { return handover_; }
  [[nodiscard]] const grid::NodeBox& band() const { return band_; }
  // Partners within this distance (pair cutoff plus skin) are exchanged.
  [[nodiscard]] double reach() const { return reach_; }
  [[nodiscard]] const std::vector<std::string>& group_names() const { return model_.group_names; }
  [[nodiscard]] const std::vector<DpdModel::GroupMotion>& group_motions() const {
    return model_.group_motions;
  }
  [[nodiscard]] std::uint32_t group_mask(const std::string& name) const {
    return model_.group_mask(name);
  }
  // The whole body's extent along each axis (outermost sites plus half a
  // plane spacing each side), before the split.
  [[nodiscard]] const std::array<double, 3>& body_extent() const { return extent_; }
  // The whole body's sites times a³/4 (each MPM point's volume), before
  // the split: the volume its crystal fills at the run's lattice constant,
  // whatever its surfaces' thermal excursions.
  [[nodiscard]] double nominal_volume() const { return nominal_volume_; }
  [[nodiscard]] double dpd_particles() const { return dpd_count_; }
  [[nodiscard]] double mpm_points() const { return mpm_count_; }

  // Before step `step`: the rigid groups on a velocity ramp take that
  // step's velocity.
  void ramp_grips(std::int64_t step);

  [[nodiscard]] DpdEngine& engine() { return *engine_; }
  [[nodiscard]] DpdGridStep& grid() { return *grid_; }
  [[nodiscard]] ConcurrentDpdSide& side() { return *side_; }

 private:
  coupling::ConcurrentParams cp_;
  coupling::BodyHandover handover_;
  grid::NodeBox band_;
  double reach_ = 0.0;
  DpdModel model_;  // its particles and pair style moved into the engine
  std::array<double, 3> extent_{};
  double nominal_volume_ = 0.0;
  double dpd_count_ = 0.0, mpm_count_ = 0.0;
  std::unique_ptr<DpdEngine> engine_;
  std::unique_ptr<DpdGridStep> grid_;
  std::unique_ptr<ConcurrentDpdSide> side_;
};

}  // namespace pbms::dpd
