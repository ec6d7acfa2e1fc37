// Loads and constraints of an MPM step, in plain data the solver applies.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "pbms/grid/material_points.hpp"
#include "pbms/grid/regular_grid.hpp"

namespace pbms::grid {

// Grid nodes in `nodes` get the velocity components marked in `axis`
// prescribed (0 for a fixed support). Applied to nodal momentum and force,
// so the constraint holds both in the update and in the remap.
struct NodeConstraint {
  NodeBox nodes;
  std::array<bool, 3> axis{false, false, false};
  Vec3 velocity{0.0, 0.0, 0.0};
};

// A force on every point of a group, mapped to the grid with N: a traction
// integrated over a face is its total divided by the group's point count
// (the caller knows the count over all ranks).
struct PointLoad {
  uint32_t group_mask = 0;
  Vec3 force_per_point{0.0, 0.0, 0.0};  // eV/Å in metal units
};

// Points of a group whose velocity components are prescribed (rigid grips,
// flyers): their velocity is reset after each update.
struct PointVelocity {
  uint32_t group_mask = 0;
  std::array<bool, 3> axis{false, false, false};
  Vec3 velocity{0.0, 0.0, 0.0};
};

struct BoundaryConditions {
  std::vector<NodeConstraint> nodes;
  std::vector<PointLoad> loads;
  std::vector<PointVelocity> point_velocities;
  Vec3 body_acceleration{0.0, 0.0, 0.0};  // gravity-like, Å/ps^2
  // A force on each point (eV/Å), indexed like the points, mapped to the
  // nodes with N as the other external forces are: the pair forces of the
  // DPD particles of the DPD/MPM-grid model (s-3b). Empty: none. The
  // caller keeps the forces alive over the step.
  std::span<const Vec3> point_forces;
};

}  // namespace pbms::grid
