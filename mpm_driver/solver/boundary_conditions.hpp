// Loads and constraints of an MPM step, in plain data the solver applies.
#pragma once

#include <array>
#include <vector>

#include "material_points.hpp"
#include "pbms/grid/regular_grid.hpp"

namespace pbms::mpm {

// Grid nodes in `nodes` get the velocity components marked in `axis`
// prescribed (0 for a fixed support). Applied to nodal momentum and force,
// so the constraint holds both in the update and in the remap.
struct NodeConstraint {
  grid::NodeBox nodes;
  std::array<bool, 3> axis{false, false, false};
  Vec3 velocity{0.0, 0.0, 0.0};
};

// A total force spread evenly over a set of points (an end load, a traction
// integrated over the face it acts on), mapped to the grid with N.
struct PointLoad {
  std::vector<size_t> points;
  Vec3 total_force{0.0, 0.0, 0.0};  // eV/Å
};

// Points whose velocity components are prescribed (rigid grips, flyers).
struct PointVelocity {
  std::vector<size_t> points;
  std::array<bool, 3> axis{false, false, false};
  Vec3 velocity{0.0, 0.0, 0.0};
};

struct BoundaryConditions {
  std::vector<NodeConstraint> nodes;
  std::vector<PointLoad> loads;
  std::vector<PointVelocity> point_velocities;
  Vec3 body_acceleration{0.0, 0.0, 0.0};  // gravity-like, Å/ps^2
};

}  // namespace pbms::mpm
