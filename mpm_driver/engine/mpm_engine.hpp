// The decomposed MPM engine the mpm_driver stages run: the grid split over
// the driver's ranks, the sums of the nodes neighbouring boxes share, the
// solver, the material points this rank owns and their migration between
// ranks. The MPI stays in the partition, halo-sum and migration classes.
//
// A stage calls step(); a coupling scheme calls the phases one by one and
// adds another program's part of the nodal sums between them.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>

#include "pbms/grid/grid_partition.hpp"
#include "pbms/grid/halo_sum.hpp"
#include "pbms/grid/mpm_solver.hpp"
#include "stage/mpm_model.hpp"

namespace pbms::mpm {

class MpmEngine {
 public:
  // Every rank passes the same model (every point of every body, in id
  // order); each keeps the points its cells own. `comm` must outlive the
  // engine.
  MpmEngine(MPI_Comm comm, MpmModel model, MaterialSet materials);
  MpmEngine(const MpmEngine&) = delete;
  MpmEngine& operator=(const MpmEngine&) = delete;

  // One step: the phases below in order, then the migration.
  void step(double dt);

  // The solver's phases on this rank's points (MpmSolver), then the
  // migration of points that left this rank's cells. Collective.
  void begin_step() { solver_->begin_step(model_.points); }
  void map_to_grid(double dt) { solver_->map_to_grid(model_.points, model_.bc, dt); }
  void complete_nodal_sums() { solver_->complete_nodal_sums(); }
  void update_nodes(double dt) { solver_->update_nodes(model_.bc, dt); }
  void map_to_points(double dt) { solver_->map_to_points(model_.points, model_.bc, dt); }
  void complete_remap_sums() { solver_->complete_remap_sums(); }
  void update_stress_and_move(double dt) {
    solver_->update_stress_and_move(model_.points, model_.bc, dt);
  }
  // update_stress_and_move in the midpoint move's two halves, for a
  // coupling scheme that adds another program's midpoint sums between them.
  void update_stress_and_map_midpoints(double dt) {
    solver_->update_stress_and_map_midpoints(model_.points, model_.bc, dt);
    solver_->complete_midpoint_sums();
  }
  void move_from_midpoints(double dt) {
    solver_->move_from_midpoints(model_.points, model_.bc, dt);
  }
  void migrate();

  // What a checkpoint holds of the engine: each rank's points in the order
  // it stores them, as rows of kStateWidth (id, x, v, mass, volume0, F,
  // stress, density, plastic strain, internal energy, material, groups,
  // work). A checkpoint keeps them rank after rank, with how many each
  // rank held (State, for restore_state), and the step count.
  static constexpr std::size_t kStateWidth = 30;
  struct State {
    std::vector<double> rows;    // every rank's, rank after rank
    std::vector<double> counts;  // per rank
  };
  [[nodiscard]] std::vector<double> own_rows() const;
  // Takes `state` (every rank the same) as the points after `steps` steps.
  // On as many ranks as wrote it each rank takes back its own points in
  // their order, so the nodal sums run as before and the run goes on bit
  // for bit; on another rank count the points go to the owners of their
  // cells in id order, and the sums differ by round-off.
  void restore_state(const State& state, std::int64_t steps);

  // The largest stable time step over every rank's points (CFL bound).
  [[nodiscard]] double stable_time_step() const;

  [[nodiscard]] grid::MaterialPoints& points() { return model_.points; }
  [[nodiscard]] const grid::MaterialPoints& points() const { return model_.points; }
  [[nodiscard]] const MpmModel& model() const { return model_; }
  // The loads a coupling scheme adds to (point forces from another program).
  [[nodiscard]] grid::BoundaryConditions& boundary_conditions() { return model_.bc; }
  [[nodiscard]] const grid::BoundaryConditions& boundary_conditions() const { return model_.bc; }
  [[nodiscard]] grid::MpmSolver& solver() { return *solver_; }
  [[nodiscard]] const grid::MpmSolver& solver() const { return *solver_; }
  [[nodiscard]] const grid::GridPartition& partition() const { return partition_; }
  // The nodes this rank writes (each node of the grid on one rank only).
  [[nodiscard]] grid::NodeBox owned_nodes() const { return partition_.owned_nodes_of(rank_); }
  [[nodiscard]] std::int64_t total_points() const { return total_points_; }
  [[nodiscard]] std::int64_t step_count() const { return steps_; }
  [[nodiscard]] MPI_Comm comm() const { return comm_; }
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int ranks() const { return ranks_; }

 private:
  void keep_own_points();
  [[nodiscard]] grid::GridPatch patch();

  MPI_Comm comm_;
  int rank_ = 0;
  int ranks_ = 1;
  MpmModel model_;
  std::int64_t total_points_ = 0;
  std::int64_t steps_ = 0;
  grid::GridPartition partition_;
  mpi::HaloSum halo_;
  std::unique_ptr<grid::MpmSolver> solver_;
};

}  // namespace pbms::mpm
