// mpm_driver's side of a concurrent DPD/MPM step: the MPM engine's phases
// on the shared grid, its points offered as pair partners to the DPD
// particles near the interface, and (momentum-conserving treatment) the
// reactions of those pairs applied to the points as point forces.
#pragma once

#include "engine/mpm_engine.hpp"
#include "pbms/coupling/coupling_side.hpp"

namespace pbms::mpm {

class ConcurrentMpmSide : public coupling::ContinuumSide {
 public:
  // The engine must outlive the side.
  ConcurrentMpmSide(MpmEngine& engine, double dt);

  void compute_forces() override {}
  void map_to_grid() override;
  [[nodiscard]] coupling::NodalRecords nodal_records() override;
  void update_and_map_back() override;
  void finish_step() override;

  [[nodiscard]] Points partner_points() const override;
  [[nodiscard]] coupling::SpaceBox points_box() const override;
  void take_reactions(std::vector<coupling::Vec3> force) override;

 private:
  MpmEngine& engine_;
  double dt_;
  std::vector<Vec3> reactions_;
};

}  // namespace pbms::mpm
