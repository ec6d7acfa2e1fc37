// One program's part of a concurrent DPD/MPM step, as a coupling scheme
// calls it (METHOD.md §3). Both sides map to one grid; the DPD side's
// particles may also take the MPM side's points as pair partners (the
// interface treatment). Each side's engine implements these phases with
// its own ranks' sums inside them; what crosses between the sides is the
// CouplingLink's business.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <vector>

#include "pbms/coupling/point_ghosts_across_programs.hpp"
#include "pbms/grid/mpm_solver.hpp"
#include "pbms/grid/node_lanes.hpp"
#include "pbms/grid/regular_grid.hpp"

namespace pbms::coupling {

// How the DPD and MPM regions of one body meet.
enum class InterfaceTreatment {
  kNone,  // the shared grid nodes alone join them
  // Seed (s-15)–(s-18): a DPD particle takes conservative, dissipative and
  // random pair forces from every MPM point within the cutoff; the point
  // feels nothing back, so momentum is not conserved exactly.
  kSeed,
  // As kSeed, and each such pair force acts back, equal and opposite, on
  // the MPM point, mapped to the nodes with that point's shape functions.
  kMomentumConserving,
};

// How the two sides' materials move at a node both reach.
enum class GridFields {
  // One velocity: their nodal sums add (one body split in two regions).
  kShared,
  // Each side its own velocity, meeting by frictionless contact
  // (grid/frictionless_contact.hpp): a gas that slides along a body it
  // cannot enter.
  kFrictionlessContact,
};

// A side's nodal records between its phases: per node of `nodes` (global
// indices, i fastest), `stride` doubles in the grid step's lane layout
// (grid::sums: mass, momentum, force, and the axes its rigid groups hold
// there as a sum of 1 (x), 2 (y) and 4 (z)) after map_to_grid; the
// momentum lanes hold the remapped momentum after map_back.
struct NodalRecords {
  double* data = nullptr;
  int stride = 0;
  grid::NodeBox nodes;
};

// A side's holds, per node: the held axes, then the held velocity on them
// (the grid step's records, grid::MpmSolver::held_nodes).
inline constexpr int kHeldLanes = grid::MpmSolver::kHeldStride;

class GridSide {
 public:
  virtual ~GridSide() = default;
  // Pair forces for a particle side; nothing for a continuum side.
  virtual void compute_forces() = 0;
  // Mass, momentum and internal force to the nodes, summed over this
  // side's own ranks (s-1 to s-3a/b).
  virtual void map_to_grid() = 0;
  [[nodiscard]] virtual NodalRecords nodal_records() = 0;
  // Nodal update with this side's conditions and rigid groups (s-4 to
  // s-6; a free rigid body's balance).
  virtual void update_nodes() = 0;
  // After update_nodes, when the link asks (some rigid group holds a node
  // of the band): what this side holds, per node of nodal_records()'
  // nodes, kHeldLanes doubles (the held axes as a sum of 1 (x), 2 (y) and
  // 4 (z), then the velocity on them), to which the link adds the other
  // side's.
  [[nodiscard]] virtual NodalRecords held_nodes() = 0;
  // Holds the nodes the other side holds (when held_nodes was asked for),
  // then grid to points and the remapped momentum summed over this side's
  // ranks (s-7 to s-10).
  virtual void map_back() = 0;
  // Nodal velocities and stresses (s-11 to s-14) and, with the midpoint
  // move, half a move and the mass and momentum at the midpoints summed
  // over this side's ranks (the link then adds the other side's); with the
  // step-start move the move itself.
  virtual void map_at_midpoints() = 0;
  // The midpoint move's move, from the start with the grid velocity at the
  // midpoint; the step is done.
  virtual void finish_step() = 0;
  // GridFields::kFrictionlessContact, after map_to_grid: this side's mass
  // gradient (3 doubles per node of nodal_records()' nodes), and the
  // buffers the link fills with the other side's sums (nodal_records'
  // lanes) and mass gradient.
  struct ContactRecords {
    NodalRecords gradient;
    NodalRecords other_sums;
    NodalRecords other_gradient;
  };
  [[nodiscard]] virtual ContactRecords contact_records() = 0;
  // The ranks of this side's program.
  [[nodiscard]] virtual MPI_Comm comm() const = 0;
  // Whether the partners must be chosen afresh this step (this side moved
  // too far since they were, or its particles changed rank); a partner set
  // kept lets the DPD side keep its neighbour list. Collective over comm().
  [[nodiscard]] virtual bool wants_new_partners() = 0;
};

// A grid step's contact fields as a side offers them.
inline GridSide::ContactRecords contact_records_of(const grid::MpmSolver::ContactFields& f) {
  const auto rec = [](const grid::MpmSolver::NodalSums& s) {
    return NodalRecords{s.data, s.stride, s.nodes};
  };
  return {rec(f.gradient), rec(f.other_sums), rec(f.other_gradient)};
}

// The side whose particles take pair partners (DPD).
class ParticleSide : public GridSide {
 public:
  // The box this rank needs partners around and the periodic lengths along
  // which it needs their images (0 where its own neighbour list wraps).
  [[nodiscard]] virtual SpaceBox partner_box() const = 0;
  [[nodiscard]] virtual PeriodicLengths partner_images() const = 0;
  // This step's partners, before compute_forces: a new set, or the last
  // set moved (same points, same order).
  virtual void take_partners(const std::vector<GhostPoint>& partners) = 0;
  virtual void move_partners(const std::vector<GhostPoint>& partners) = 0;
  // After compute_forces: the force on each partner from this side's
  // particles, in the order given.
  [[nodiscard]] virtual std::vector<Vec3> partner_forces() const = 0;
};

// The side whose points serve as partners (MPM).
class ContinuumSide : public GridSide {
 public:
  struct Points {
    const std::vector<std::int64_t>& id;
    const std::vector<Vec3>& x;
    const std::vector<Vec3>& v;
    const std::vector<double>& mass;
  };
  // Positions continuous in time (not wrapped on periodic axes) since the
  // partners were last chosen.
  [[nodiscard]] virtual Points partner_points() const = 0;
  // The partners were chosen afresh from partner_points().
  virtual void partners_renewed() = 0;
  // The box this rank's points lie in.
  [[nodiscard]] virtual SpaceBox points_box() const = 0;
  // Before map_to_grid: the force on each point (indexed like
  // partner_points) from the particles it partnered this step.
  virtual void take_reactions(std::vector<Vec3> force) = 0;
};

}  // namespace pbms::coupling
