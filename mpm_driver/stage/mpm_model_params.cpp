#include "mpm_model_params.hpp"

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/geometry/region_yaml.hpp"

namespace pbms::mpm {
namespace {

grid::Vec3 vec3(const YAML::Node& n) {
  const auto v = n.as<std::vector<double>>();
  return {v.at(0), v.at(1), v.at(2)};
}

std::size_t axis_index(const std::string& a) {
  if (a == "x") return 0;
  if (a == "y") return 1;
  if (a == "z") return 2;
  throw Error(fmt::format("'{}' is not an axis (x, y or z)", a));
}

std::array<bool, 3> axes_of(const YAML::Node& n) {
  std::array<bool, 3> out{false, false, false};
  if (n) {
    for (const auto& a : n) out[axis_index(a.as<std::string>())] = true;
  }
  return out;
}

NodesCondition nodes_from_yaml(const YAML::Node& c) {
  NodesCondition n;
  n.region = geometry::region_from_yaml(c["region"]);
  n.axes = axes_of(c["axes"]);
  if (c["velocity"]) n.velocity = vec3(c["velocity"]);
  return n;
}

GroupVelocityCondition group_velocity_from_yaml(const YAML::Node& c) {
  GroupVelocityCondition g;
  g.group = c["group"].as<std::string>();
  g.axes = axes_of(c["axes"]);
  g.velocity = vec3(c["velocity"]);
  g.ramp_time = c["ramp_time"].as<double>(0.0);
  return g;
}

GroupForceCondition group_force_from_yaml(const YAML::Node& c) {
  GroupForceCondition g;
  g.group = c["group"].as<std::string>();
  g.force = vec3(c["force"]);
  return g;
}

}  // namespace

GridParams GridParams::from_yaml(const YAML::Node& g) {
  GridParams r;
  r.origin = vec3(g["origin"]);
  r.cell_size = g["cell_size"].as<double>();
  const auto cells = g["cells"].as<std::vector<int>>();
  r.cells = {cells.at(0), cells.at(1), cells.at(2)};
  r.periodic = axes_of(g["periodic"]);
  return r;
}

AxialMode AxialMode::from_yaml(const YAML::Node& mode) {
  AxialMode r;
  r.axis = axis_index(mode["axis"].as<std::string>());
  r.amplitude = mode["amplitude"].as<double>();
  r.fixed_end = mode["fixed_end"].as<double>();
  r.length = mode["length"].as<double>();
  return r;
}

BodyParams BodyParams::from_yaml(const YAML::Node& b) {
  BodyParams r;
  r.name = b["name"].as<std::string>();
  r.material = b["material"].as<std::string>();
  r.region = geometry::region_from_yaml(b["region"]);
  r.points_per_cell = b["points_per_cell"].as<std::vector<int>>();
  r.pressure = b["pressure"].as<double>();
  r.velocity = vec3(b["velocity"]);
  if (b["axial_mode"]) r.axial_mode = AxialMode::from_yaml(b["axial_mode"]);
  return r;
}

GroupParams GroupParams::from_yaml(const YAML::Node& g) {
  return {g["name"].as<std::string>(), geometry::region_from_yaml(g["region"])};
}

std::vector<Condition> MpmModelParams::conditions_from_yaml(const YAML::Node& boundary) {
  std::vector<Condition> out;
  for (const auto& c : boundary) {
    const auto kind = c["kind"].as<std::string>();
    if (kind == "nodes") {
      out.emplace_back(nodes_from_yaml(c));
    } else if (kind == "group_velocity") {
      out.emplace_back(group_velocity_from_yaml(c));
    } else if (kind == "group_force") {
      out.emplace_back(group_force_from_yaml(c));
    }
  }
  return out;
}

MpmModelParams MpmModelParams::from_yaml(const YAML::Node& params) {
  MpmModelParams m;
  m.metal_units = params["units"].as<std::string>() == "metal";
  m.grid = GridParams::from_yaml(params["grid"]);
  m.shape_function = params["shape_function"].as<std::string>();

  grid::SolverOptions& o = m.options;
  o.stress_update = params["stress_update"].as<std::string>() == "first"
                        ? grid::StressUpdate::kFirst
                        : grid::StressUpdate::kLast;
  o.flip = params["flip"].as<double>();
  o.ddmp = params["gradient"].as<std::string>() == "ddmp";
  o.ddmp_face_vanishing = params["ddmp_blend"].as<std::string>() == "face_vanishing";
  o.small_mass_fraction = params["small_mass_fraction"].as<double>();
  o.units = m.metal_units ? grid::UnitSystem::metal() : grid::UnitSystem{};

  for (const auto& g : params["groups"]) m.groups.push_back(GroupParams::from_yaml(g));
  for (const auto& b : params["bodies"]) m.bodies.push_back(BodyParams::from_yaml(b));
  m.boundary = conditions_from_yaml(params["boundary"]);
  m.body_acceleration = vec3(params["body_acceleration"]);
  return m;
}

}  // namespace pbms::mpm
