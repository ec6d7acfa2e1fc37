// The DPD/MPM-grid model (seed §2.4 and §5.2; METHOD.md §3): DPD particles
// advanced through an MPM background grid instead of by velocity Verlet.
//
// Each step the engine computes the pair forces (conservative,
// dissipative and random, the last two from the particles' own
// velocities) at the current positions. The particles' mass, momentum and
// pair forces go to the nodes with the shape functions, the forces where
// an MPM point's stress divergence would go (s-3b); the nodal momentum
// update gives nodal accelerations and velocities; each particle takes the
// FLIP/PIC velocity update and moves with the grid velocity (s-6 to s-9):
// the updated nodal velocity at the step's start, or (settings.move, on
// the engine's own grid) the new momentum's grid velocity at the move's
// midpoint, which keeps a crystal's energy where particles share nodes.
// The grid pass is the MPM solver's own phased step, with the particles
// as StresslessParticle points: a concurrent run treats DPD particles and
// MPM points alike. As the cell edge shrinks the model tends to DPD-only.
//
// Rigid groups enter in one way, wherever they appear: as prescribed-
// velocity groups of the grid step (the particles keep the group's
// velocity, and the nodes they touch move with it), as an MPM grip does;
// a free rigid body's velocity is then the one that needs no force to hold
// its nodes (balance_free_bodies), so momentum is conserved.
//
// On several ranks the engine takes the grid partition's split
// (DomainDecomposition from a GridPartition) and rebuilds whenever a
// particle has left its rank's cells, so that at each grid pass every
// particle lies in its own rank's cells: each rank's solver works on
// partition().nodes_of(rank), and the nodal sums over ranks are the
// HaloSum an MPM run uses (GridPatch::sum_shared), which also folds the
// periodic faces on one rank. Free rigid bodies sum their nodes' mass and
// holding force over ranks.
// Particles exactly on a node plane are the one place where ranks may
// differ by more than round-off: a rigid group's particle there gives the
// node beyond a weight of round-off size, which marks the node rigid or
// not depending on how each rank's patch rounds.
#pragma once

#include <memory>
#include <vector>

#include "engine/dpd_engine.hpp"
#include "pbms/grid/boundary_conditions.hpp"
#include "pbms/grid/grid_partition.hpp"
#include "pbms/grid/halo_sum.hpp"
#include "pbms/grid/mpm_solver.hpp"

namespace pbms::dpd {

struct DpdGridSettings {
  double cell_size = 4.0;  // Å, the grid's cell edge h
  double flip = 1.0;       // 1: FLIP, 0: PIC
  // Cells of grid beyond the box on each free (non-periodic) axis, for
  // surfaces that move out.
  int free_axis_margin_cells = 4;
  // Rigid groups, group bits as DpdParticles::group_mask: each moves at
  // its velocity on the grid (PointVelocity on every axis). A free body's
  // velocity is, each step, the momentum of the nodes it holds over their
  // mass (a flyer: momentum conserved with the material it sweeps); the
  // others keep theirs (grips, walls).
  struct RigidGroup {
    std::uint32_t mask = 0;
    grid::Vec3 velocity{0.0, 0.0, 0.0};
    bool free_body = false;
  };
  std::vector<RigidGroup> rigid;
  // Where the particles take the grid velocity they move with
  // (grid::PointMove). On a grid shared with another program, kMidpoint
  // needs its midpoint sums completed across the link (CouplingScheme).
  grid::PointMove move = grid::PointMove::kStepStart;
  // The particles are one field of a frictionless contact with another
  // program's points, whose mass gives the surface (grid::ContactField).
  bool contact = false;
};

class DpdGridStep {
 public:
  // The grid over the engine's box: whole cells on periodic axes, a margin
  // beyond it on free ones. On several ranks the engine's particles move
  // to the partition's sub-boxes (collective). Throws pbms::Error when a
  // periodic box length is not a whole number of cells (to 1e-9), when the
  // cell edge is not below the DPD cutoff (seed §2.4), or when a sub-box
  // that passes ghosts on is thinner than cutoff + skin.
  DpdGridStep(DpdEngine& engine, const DpdGridSettings& settings);
  // On a given grid (a concurrent run's shared one) with its periodic
  // axes, which must be the box's; this rank's nodes and their sums come
  // from the partition of that grid over the engine's ranks.
  // settings.cell_size must be the grid's spacing, and on each periodic
  // axis the grid must span the box. Throws as above.
  DpdGridStep(DpdEngine& engine, const DpdGridSettings& settings, const grid::RegularGrid& grid,
              const std::array<bool, 3>& periodic);

  // One step of the engine's dt: the four phases below in order. Throws
  // pbms::Error naming the particle when one leaves the grid.
  void step();

  // The phases of step(), for a coupling scheme that adds another
  // program's nodal sums between them.
  void compute_forces();  // pair forces, free bodies pushed
  void map_to_grid();     // mass, momentum, pair forces to the nodes (s-1, s-2, s-3b)
  void update_nodes();    // nodal update, rigid groups held, free bodies balanced (s-4 to s-6)
  void map_back();        // grid to particles, remap (s-7 to s-10)
  // The stress update and, with the midpoint move, half a move and the
  // map at the midpoints (this program's part of those sums, complete
  // over its ranks; a coupling scheme adds the other program's).
  void map_at_midpoints();
  void finish_step();  // move with the grid velocity (s-11), step counted, ghosts
                       // follow

  // The velocity a rigid (not free) group of settings.rigid moves at from
  // the next step on (a grip on a velocity ramp).
  void set_rigid_velocity(std::uint32_t mask, const grid::Vec3& v);
  // The rigid groups' velocities now, settings.rigid's order, three each (a
  // free body's changes every step, a grip's on its ramp), for a
  // checkpoint; and back, as the velocities the next step holds them at.
  [[nodiscard]] std::vector<double> rigid_velocities() const;
  void restore_rigid_velocities(const std::vector<double>& v);

  // Whether each compute_forces also tallies the pair energy
  // (DpdEngine::last_tally), for a ledger kept every step: a few operations
  // a pair in the pass the step makes anyway, where a pass of its own would
  // cost a whole one.
  void tally_each_step(bool on) { tally_ = on ? Tally::kEnergy : Tally::kForcesOnly; }

  // Whether the next compute_forces will rebuild the neighbour list (a
  // particle moved more than half the skin, or left its rank's cells).
  // Collective over the engine's ranks.
  [[nodiscard]] bool list_needs_rebuild();

  // Nodal records (MpmSolver::nodal_sums) between map_to_grid and
  // update_nodes, and the remapped momentum after map_back.
  [[nodiscard]] grid::MpmSolver::NodalSums nodal_sums() { return solver_->nodal_sums(); }
  [[nodiscard]] grid::MpmSolver::ContactFields contact_fields() {
    return solver_->contact_fields();
  }

  // Between update_nodes and map_back: the nodes the rigid groups hold
  // (MpmSolver::held_nodes), and holding those another program holds.
  void held_nodes(double* records) const { solver_->held_nodes(bc_, records); }
  void hold_nodes_of_others(const double* records) {
    solver_->hold_nodes_of_others(records, engine_.settings().dt);
  }

  [[nodiscard]] const grid::RegularGrid& grid() const { return solver_->grid(); }
  // The split of the grid over the engine's ranks, which is also the
  // engine's decomposition; nodal_sums() covers nodes_of(this rank).
  [[nodiscard]] const grid::GridPartition& partition() const { return *partition_; }
  [[nodiscard]] const grid::MpmSolver& solver() const { return *solver_; }

 private:
  void init(const grid::RegularGrid& grid, const std::array<bool, 3>& periodic);
  // Points as many as the owned particles, with their state and fields.
  void load_points();
  void store_points();
  // Rebuilds when left_own_cells() or the engine's skin asks for it, and
  // moves the ghosts along otherwise (collective).
  void refresh_neighbours();
  // Whether a particle on any rank has left its rank's cells since the
  // last rebuild (collective; false on one rank). The grid pass needs each
  // particle on the rank whose patch holds it, so that forces a rebuild
  // (wrap, migration, ghosts, list), as a move of half the skin does.
  [[nodiscard]] bool left_own_cells() const;
  // Free bodies: after the nodal update, the velocity that makes the
  // force holding their nodes zero (collective).
  void balance_free_bodies();

  DpdEngine& engine_;
  DpdGridSettings settings_;
  // Addressed by halo_ and solver_, so kept at one place.
  std::unique_ptr<grid::GridPartition> partition_;
  std::unique_ptr<mpi::HaloSum> halo_;
  std::unique_ptr<grid::MpmSolver> solver_;
  grid::MaterialPoints points_;
  double point_volume_ = 0.0;  // Å³; only a stress term uses it, and that is zero
  grid::BoundaryConditions bc_;
  std::vector<grid::Vec3> forces_;
  Tally tally_ = Tally::kForcesOnly;
};

}  // namespace pbms::dpd
