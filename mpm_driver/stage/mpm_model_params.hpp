// The part of an mpm_run stage's checked parameters that build_model turns
// into the model: the grid, the solver options, the bodies, the groups and
// the boundary conditions (the schema is MpmRunStage::spec(), in
// mpm_run_spec.cpp). Read once, before any of it is checked against the
// others: names that clash, unknown materials and empty regions are
// build_model's to refuse, in the order it meets them.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/geometry/region.hpp"
#include "pbms/grid/mpm_solver.hpp"

namespace pbms::mpm {

struct GridParams {
  grid::Vec3 origin{0.0, 0.0, 0.0};
  double cell_size = 1.0;
  std::array<int, 3> cells{1, 1, 1};
  std::array<bool, 3> periodic{false, false, false};

  static GridParams from_yaml(const YAML::Node& grid);
};

// The first axial mode of a fixed-free bar added to a body's velocity.
struct AxialMode {
  std::size_t axis = 0;
  double amplitude = 0.0;
  double fixed_end = 0.0;
  double length = 1.0;

  static AxialMode from_yaml(const YAML::Node& mode);
};

struct BodyParams {
  std::string name;
  std::string material;
  geometry::RegionPtr region;
  // As given: one number or x, y, z; build_model spreads one number to all.
  std::vector<int> points_per_cell;
  double pressure = 0.0;
  grid::Vec3 velocity{0.0, 0.0, 0.0};
  std::optional<AxialMode> axial_mode;

  static BodyParams from_yaml(const YAML::Node& body);
};

struct GroupParams {
  std::string name;
  geometry::RegionPtr region;

  static GroupParams from_yaml(const YAML::Node& group);
};

// The boundary conditions, one struct per kind.
struct NodesCondition {
  geometry::RegionPtr region;
  std::array<bool, 3> axes{false, false, false};
  std::optional<grid::Vec3> velocity;  // empty: NodeConstraint's default
};

struct GroupVelocityCondition {
  std::string group;
  std::array<bool, 3> axes{false, false, false};
  grid::Vec3 velocity{0.0, 0.0, 0.0};
  double ramp_time = 0.0;
};

struct GroupForceCondition {
  std::string group;
  grid::Vec3 force{0.0, 0.0, 0.0};  // the total, shared by the group's points
};

using Condition = std::variant<NodesCondition, GroupVelocityCondition, GroupForceCondition>;

struct MpmModelParams {
  bool metal_units = true;
  GridParams grid;
  std::string shape_function = "linear";
  grid::SolverOptions options;  // its units follow metal_units
  std::vector<GroupParams> groups;
  std::vector<BodyParams> bodies;
  std::vector<Condition> boundary;
  grid::Vec3 body_acceleration{0.0, 0.0, 0.0};

  // From the stage's whole parameter map.
  static MpmModelParams from_yaml(const YAML::Node& params);
  // The boundary list; a condition of an unknown kind is left out.
  static std::vector<Condition> conditions_from_yaml(const YAML::Node& boundary);
};

}  // namespace pbms::mpm
