// An mpm_run stage's parameters turned into solver inputs: the grid, the
// materials, every material point of every body (the same on every rank, in
// a fixed order, so that global ids do not depend on the decomposition),
// the named groups and the boundary conditions. Pure: no MPI, no files.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mpm_model_params.hpp"
#include "pbms/grid/mpm_solver.hpp"

namespace pbms::mpm {

// The materials: a stage's `materials:` entries in solver units.
struct MaterialSet {
  std::vector<std::unique_ptr<grid::Material>> models;
  std::vector<std::string> names;
  std::vector<double> density;  // solver units
};

struct MpmModel {
  grid::RegularGrid grid{{0, 0, 0}, 1.0, {1, 1, 1}};
  std::array<bool, 3> periodic{false, false, false};
  bool metal_units = true;
  std::string shape_function = "linear";
  grid::SolverOptions options;
  grid::MaterialPoints points;
  std::vector<std::string> group_names;  // bit g of MaterialPoints::groups
  std::vector<int64_t> group_sizes;      // points per group, all ranks
  grid::BoundaryConditions bc;
  // For each bc.point_velocities entry, the group it holds (for probes).
  std::vector<std::string> point_velocity_groups;
  // For each bc.point_velocities entry, its full velocity and the time it
  // is reached over from rest (0: at once; velocity_ramp.hpp).
  struct Ramp {
    double time = 0.0;
    grid::Vec3 velocity{0.0, 0.0, 0.0};
  };
  std::vector<Ramp> point_velocity_ramps;

  [[nodiscard]] uint32_t group_mask(const std::string& name) const;  // throws if unknown
};

// Sets each ramped point velocity of `bc` to its value for step `step`
// (before that step); entries past their ramp are left alone.
void ramp_point_velocities(const MpmModel& model, grid::BoundaryConditions& bc, std::int64_t step,
                           double dt);
// The held groups' velocities now (three each, in bc's order), for a
// checkpoint: a ramped group's after its ramp is not the one it starts at.
// And back; throws pbms::Error when the counts differ.
[[nodiscard]] std::vector<double> point_velocities_of(const grid::BoundaryConditions& bc);
void restore_point_velocities(grid::BoundaryConditions& bc, const std::vector<double>& v);

// Reads the stage's `materials` entries that `bodies` use, converting
// densities and moduli to solver units when `metal_units`.
[[nodiscard]] MaterialSet materials_from_yaml(const std::vector<std::string>& names,
                                              const std::vector<YAML::Node>& entries,
                                              bool metal_units);

// Throws pbms::Error for names that clash, a body of a material not in
// `materials`, a body or a `nodes` region that catches nothing, an unknown
// group, or a loaded group without points.
[[nodiscard]] MpmModel build_model(const MpmModelParams& params, MaterialSet& materials);

}  // namespace pbms::mpm
