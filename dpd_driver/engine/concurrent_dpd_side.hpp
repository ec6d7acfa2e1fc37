// dpd_driver's side of a concurrent DPD/MPM step: the DPD/MPM-grid model
// (DpdGridStep) on the shared grid, whose particles take the MPM side's
// points as pair partners when the interface treatment is on.
#pragma once

#include "engine/dpd_engine.hpp"
#include "engine/dpd_grid_step.hpp"
#include "pbms/coupling/coupling_side.hpp"
#include "pbms/coupling/held_nodes.hpp"

namespace pbms::dpd {

class ConcurrentDpdSide : public coupling::ParticleSide {
 public:
  // `partner_type` is the pair-style type the MPM points pair as. Both
  // must outlive the side.
  ConcurrentDpdSide(DpdEngine& engine, DpdGridStep& grid, int partner_type);

  void compute_forces() override { grid_.compute_forces(); }
  void map_to_grid() override { grid_.map_to_grid(); }
  [[nodiscard]] coupling::NodalRecords nodal_records() override;
  [[nodiscard]] ContactRecords contact_records() override {
    return coupling::contact_records_of(grid_.contact_fields());
  }
  void update_nodes() override;
  [[nodiscard]] coupling::NodalRecords held_nodes() override;
  void map_back() override;
  void map_at_midpoints() override { grid_.map_at_midpoints(); }
  void finish_step() override { grid_.finish_step(); }
  [[nodiscard]] MPI_Comm comm() const override { return engine_.comm(); }
  [[nodiscard]] bool wants_new_partners() override { return grid_.list_needs_rebuild(); }

  [[nodiscard]] coupling::SpaceBox partner_box() const override;
  [[nodiscard]] coupling::PeriodicLengths partner_images() const override;
  void take_partners(const std::vector<coupling::GhostPoint>& partners) override;
  void move_partners(const std::vector<coupling::GhostPoint>& partners) override;
  [[nodiscard]] std::vector<coupling::Vec3> partner_forces() const override;

 private:
  void unpack(const std::vector<coupling::GhostPoint>& partners);

  DpdEngine& engine_;
  DpdGridStep& grid_;
  int partner_type_;
  std::vector<Vec3> x_, v_;
  std::vector<std::int64_t> id_;
  coupling::HeldNodeSwap holds_;
};

}  // namespace pbms::dpd
