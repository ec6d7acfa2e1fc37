// What the MPM part of a concurrent stage measures of the gas around the
// body: the pressure it reached away from the body (the points of the
// group MpmPartOfBody::kGasAwayGroup) and over all of it, every sample,
// and the momentum the walls gave it, every step.
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

#include "engine/mpm_engine.hpp"
#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::mpm {

class GasProbe {
 public:
  // `gas_material`: the gas's material index; `away_mask`: the group of the
  // points away from the body.
  GasProbe(MPI_Comm comm, const coupling::GasParams& gas, int gas_material,
           std::uint32_t away_mask);

  // After each step: adds the walls' impulse of this rank's nodes, and
  // their inward push.
  void after_step(const MpmEngine& engine);
  // The walls' impulse since the start, this rank's share (a ledger row's).
  [[nodiscard]] const std::array<double, 3>& wall_impulse() const { return impulse_; }
  // Collective over the part's ranks.
  void sample(double t, const MpmEngine& engine);

  // gas_points, gas_pressure (and its target and error), the series and
  // wall_impulse. Collective.
  void report(StageResults& r, std::int64_t gas_points) const;
  // Collective: the impulse is summed over the ranks, and rank 0 takes it
  // back on load.
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  // The walls' impulse since the start over the part's ranks. Collective.
  [[nodiscard]] std::array<double, 3> total_impulse() const;

  MPI_Comm comm_;
  coupling::GasParams gas_;
  int material_;
  std::uint32_t away_;
  // The area of the grid's walls (Å²): its outer faces on the axes that
  // are not periodic.
  [[nodiscard]] static double wall_area(const MpmEngine& engine);

  std::array<double, 3> impulse_{};
  double push_ = 0.0;  // the walls' inward push since the last sample, this rank's
  std::vector<double> time_, away_pressure_, all_pressure_, wall_pressure_;  // ps, bar
};

}  // namespace pbms::mpm
