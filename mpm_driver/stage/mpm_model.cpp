#include "mpm_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "materials/material_registry.hpp"
#include "pbms/error.hpp"
#include "pbms/geometry/region_yaml.hpp"
#include "pbms/grid/cell_fill.hpp"
#include "pbms/units.hpp"
#include "pbms/velocity_ramp.hpp"

namespace pbms::mpm {
namespace {

grid::Vec3 vec3(const YAML::Node& n) {
  const auto v = n.as<std::vector<double>>();
  return {v.at(0), v.at(1), v.at(2)};
}

size_t axis_index(const std::string& a) {
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

}  // namespace

uint32_t MpmModel::group_mask(const std::string& name) const {
  for (size_t g = 0; g < group_names.size(); ++g) {
    if (group_names[g] == name) return 1u << g;
  }
  throw Error(fmt::format("no group named '{}'", name));
}

MaterialSet materials_from_yaml(const std::vector<std::string>& names,
                                const std::vector<YAML::Node>& entries, bool metal_units) {
  MaterialSet set;
  // Moduli stay in bar (the solver's stress unit); densities go from g/cm^3
  // to g/mol/Å^3, which UnitSystem::metal() pairs with bar.
  const double rho_factor = metal_units ? 1.0 / units::kGramPerCm3PerAmuPerA3 : 1.0;
  for (size_t i = 0; i < names.size(); ++i) {
    const YAML::Node& e = entries[i];
    const auto kind = e["kind"].as<std::string>();
    MaterialParameters p;
    for (const auto& kv : e) {
      const auto key = kv.first.as<std::string>();
      if (key == "kind" || key == "density") continue;
      p[key] = kv.second.as<double>();
    }
    try {
      set.models.push_back(MaterialRegistry::create(kind, p));
    } catch (const Error& err) {
      throw Error(fmt::format("material '{}': {}", names[i], err.what()));
    }
    set.names.push_back(names[i]);
    set.density.push_back(e["density"].as<double>() * rho_factor);
  }
  return set;
}

MpmModel build_model(const YAML::Node& params, MaterialSet& materials) {
  MpmModel m;
  m.metal_units = params["units"].as<std::string>() == "metal";
  const YAML::Node& g = params["grid"];
  const auto cells = g["cells"].as<std::vector<int>>();
  m.grid = grid::RegularGrid(vec3(g["origin"]), g["cell_size"].as<double>(),
                             {cells.at(0), cells.at(1), cells.at(2)});
  m.periodic = axes_of(g["periodic"]);
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

  // Groups first: bodies may name the groups their points join.
  std::vector<std::unique_ptr<geometry::Region>> group_regions;
  for (const auto& gn : params["groups"]) {
    const auto name = gn["name"].as<std::string>();
    if (std::find(m.group_names.begin(), m.group_names.end(), name) != m.group_names.end()) {
      throw Error(fmt::format("group '{}' is defined twice", name));
    }
    if (m.group_names.size() == 32) throw Error("at most 32 groups per stage");
    m.group_names.push_back(name);
    group_regions.push_back(region_from_yaml(gn["region"]));
  }
  // Every body is a group of its own too.
  const size_t region_groups = m.group_names.size();
  for (const auto& b : params["bodies"]) {
    const auto name = b["name"].as<std::string>();
    if (std::find(m.group_names.begin(), m.group_names.end(), name) != m.group_names.end()) {
      throw Error(fmt::format("body '{}' has the name of a group or another body", name));
    }
    if (m.group_names.size() == 32) throw Error("at most 32 groups and bodies per stage");
    m.group_names.push_back(name);
  }

  int64_t id = 0;
  size_t body_index = 0;
  for (const auto& b : params["bodies"]) {
    const auto name = b["name"].as<std::string>();
    const auto mat_name = b["material"].as<std::string>();
    const auto it = std::find(materials.names.begin(), materials.names.end(), mat_name);
    if (it == materials.names.end())
      throw Error(fmt::format("body '{}': unknown material '{}'", name, mat_name));
    const int mat = static_cast<int>(it - materials.names.begin());
    const grid::Material& model = *materials.models[static_cast<size_t>(mat)];
    const auto region = region_from_yaml(b["region"]);
    auto ppc = b["points_per_cell"].as<std::vector<int>>();
    if (ppc.size() == 1) ppc = {ppc[0], ppc[0], ppc[0]};
    const auto filled = geometry::fill_cells(*region, m.grid, {ppc.at(0), ppc.at(1), ppc.at(2)});
    if (filled.positions.empty()) {
      throw Error(fmt::format("body '{}': its region holds no material point of the grid", name));
    }
    const double pressure = b["pressure"].as<double>();
    const grid::MaterialPointState s0 =
        model.initial_state(materials.density[static_cast<size_t>(mat)], pressure);
    const grid::Vec3 v0 = vec3(b["velocity"]);
    const YAML::Node mode = b["axial_mode"];
    const uint32_t body_bit = 1u << (region_groups + body_index);
    for (size_t k = 0; k < filled.positions.size(); ++k) {
      const grid::Vec3& x = filled.positions[k];
      uint32_t bits = body_bit;
      for (size_t gi = 0; gi < region_groups; ++gi) {
        if (group_regions[gi]->contains(x)) bits |= 1u << gi;
      }
      m.points.add(id++, x, filled.volumes[k], s0, mat, bits);
      grid::Vec3 v = v0;
      if (mode) {
        // First axial mode of a bar fixed at `fixed_end` and free at
        // fixed_end + length: v = A sin(pi s / 2L).
        const size_t a = axis_index(mode["axis"].as<std::string>());
        const double sfrac = (x[a] - mode["fixed_end"].as<double>()) / mode["length"].as<double>();
        v[a] += mode["amplitude"].as<double>() * std::sin(0.5 * std::numbers::pi * sfrac);
      }
      m.points.v.back() = v;
    }
    ++body_index;
  }
  m.group_sizes.assign(m.group_names.size(), 0);
  for (const uint32_t bits : m.points.groups) {
    for (size_t gi = 0; gi < m.group_names.size(); ++gi) {
      if (bits & (1u << gi)) ++m.group_sizes[gi];
    }
  }

  // Boundary conditions.
  for (const auto& c : params["boundary"]) {
    const auto kind = c["kind"].as<std::string>();
    if (kind == "nodes") {
      // Every node whose position lies in the region.
      const auto region = region_from_yaml(c["region"]);
      grid::NodeConstraint nc;
      nc.axis = axes_of(c["axes"]);
      if (c["velocity"]) nc.velocity = vec3(c["velocity"]);
      std::array<int, 3> lo{}, hi{};
      bool any = false;
      const auto n = m.grid.nodes_per_axis();
      for (int k = 0; k < n[2]; ++k) {
        for (int j = 0; j < n[1]; ++j) {
          for (int i = 0; i < n[0]; ++i) {
            if (!region->contains(m.grid.node_position({i, j, k}))) continue;
            const std::array<int, 3> ijk{i, j, k};
            for (size_t a = 0; a < 3; ++a) {
              lo[a] = any ? std::min(lo[a], ijk[a]) : ijk[a];
              hi[a] = any ? std::max(hi[a], ijk[a] + 1) : ijk[a] + 1;
            }
            any = true;
          }
        }
      }
      if (!any) throw Error("a `nodes` boundary condition's region holds no grid node");
      nc.nodes = {lo, hi};
      m.bc.nodes.push_back(nc);
    } else if (kind == "group_velocity") {
      grid::PointVelocity pv;
      const auto group = c["group"].as<std::string>();
      pv.group_mask = m.group_mask(group);
      pv.axis = axes_of(c["axes"]);
      pv.velocity = vec3(c["velocity"]);
      m.point_velocity_ramps.push_back({c["ramp_time"].as<double>(0.0), pv.velocity});
      if (m.point_velocity_ramps.back().time > 0.0) {
        // A ramped group starts at rest on its held axes, as a DPD one does.
        pv.velocity = {0.0, 0.0, 0.0};
        for (size_t i = 0; i < m.points.size(); ++i) {
          if (!m.points.in_group(i, pv.group_mask)) continue;
          for (size_t a = 0; a < 3; ++a) {
            if (pv.axis[a]) m.points.v[i][a] = 0.0;
          }
        }
      }
      m.bc.point_velocities.push_back(pv);
      m.point_velocity_groups.push_back(group);
    } else if (kind == "group_force") {
      grid::PointLoad load;
      const auto group = c["group"].as<std::string>();
      load.group_mask = m.group_mask(group);
      const auto count = m.group_sizes[static_cast<size_t>(std::countr_zero(load.group_mask))];
      if (count == 0) throw Error(fmt::format("group '{}' has no material point to load", group));
      const grid::Vec3 total = vec3(c["force"]);
      for (size_t a = 0; a < 3; ++a)
        load.force_per_point[a] = total[a] / static_cast<double>(count);
      m.bc.loads.push_back(load);
    }
  }
  m.bc.body_acceleration = vec3(params["body_acceleration"]);
  return m;
}

void ramp_point_velocities(const MpmModel& model, grid::BoundaryConditions& bc, std::int64_t step,
                           double dt) {
  for (std::size_t k = 0; k < model.point_velocity_ramps.size(); ++k) {
    const auto& r = model.point_velocity_ramps[k];
    if (!(r.time > 0.0) || ramp_fraction(step - 1, dt, r.time) >= 1.0) continue;
    const double f = ramp_fraction(step, dt, r.time);
    for (std::size_t a = 0; a < 3; ++a) bc.point_velocities[k].velocity[a] = f * r.velocity[a];
  }
}

}  // namespace pbms::mpm
