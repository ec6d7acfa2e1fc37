// mpm_driver's side of a concurrent DPD/MPM step: the MPM engine's phases
// on the shared grid, its points offered as pair partners to the DPD
// particles near the interface, and (momentum-conserving treatment) the
// reactions of those pairs applied to the points as point forces.
#pragma once

#include <functional>

#include "engine/mpm_engine.hpp"
#include "pbms/coupling/coupling_side.hpp"
#include "pbms/coupling/ghost_force_correction.hpp"
#include "pbms/coupling/held_nodes.hpp"

namespace pbms::mpm {

class ConcurrentMpmSide : public coupling::ContinuumSide {
 public:
  // The engine must outlive the side. The partners are chosen afresh once
  // a point has moved more than half `partner_skin` (the DPD list's skin)
  // since they were, or points changed rank; 0 chooses them every step.
  // Points of material `gas_material` (the gas around the body; -1: none)
  // are no pair partners: the gas meets the body through the grid alone.
  ConcurrentMpmSide(MpmEngine& engine, double dt, double partner_skin = 0.0, int gas_material = -1);

  void compute_forces() override {}
  void map_to_grid() override;
  [[nodiscard]] coupling::NodalRecords nodal_records() override;
  [[nodiscard]] ContactRecords contact_records() override {
    return coupling::contact_records_of(engine_.solver().contact_fields());
  }
  void update_nodes() override;
  [[nodiscard]] coupling::NodalRecords held_nodes() override;
  void map_back() override;
  void map_at_midpoints() override;
  void finish_step() override;

  [[nodiscard]] MPI_Comm comm() const override { return engine_.comm(); }
  [[nodiscard]] bool wants_new_partners() override;
  [[nodiscard]] Points partner_points() const override;
  void partners_renewed() override;
  [[nodiscard]] coupling::SpaceBox points_box() const override;
  void take_reactions(std::vector<coupling::Vec3> force) override;
  // The reactions from then on pass through `c` (which must outlive the
  // side) before they reach the points; `part_of` labels the part of the
  // body a point at x belongs to (its region), whose dead loads balance.
  void correct_ghost_forces(coupling::GhostForceCorrection& c,
                            std::function<int(const grid::Vec3&)> part_of) {
    ghost_forces_ = &c;
    part_of_ = std::move(part_of);
  }

  // Forgets the followed points, as a migration does: the next step
  // chooses the partners afresh from the points as they are stored. A
  // checkpoint of a concurrent stage calls this, so that the run that wrote
  // it and a run resumed from it (which starts with nothing followed) go on
  // alike.
  void forget_followed_points() { ids_.clear(); }

 private:
  // Follows the points since the last call: positions unwrapped across
  // periodic faces. Returns false when the points changed (a migration).
  bool follow_points();

  // Without gas, every point; with gas, the body's points (partner_ lists
  // their indices and holds copies of their fields).
  void choose_partner_points() const;

  MpmEngine& engine_;
  double dt_;
  double skin_;
  int gas_;
  struct PartnerCopy {
    std::vector<std::size_t> index;
    std::vector<std::int64_t> id;
    std::vector<grid::Vec3> x, v;
    std::vector<double> mass;
  };
  mutable PartnerCopy partner_;
  std::vector<grid::Vec3> reactions_;
  coupling::HeldNodeSwap holds_;
  std::vector<std::int64_t> ids_;               // the points as last followed
  std::vector<grid::Vec3> last_x_, unwrapped_;  // wrapped as stored; continuous
  std::vector<grid::Vec3> chosen_at_;           // unwrapped_ when partners were chosen
  bool changed_ = true;                         // points changed rank since then
  coupling::GhostForceCorrection* ghost_forces_ = nullptr;
  std::function<int(const grid::Vec3&)> part_of_;
  std::vector<int> parts_;
};

}  // namespace pbms::mpm
