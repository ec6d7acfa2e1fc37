#include "mpm_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

#include <fmt/format.h>

#include "materials/material_registry.hpp"
#include "pbms/error.hpp"
#include "pbms/grid/cell_fill.hpp"
#include "pbms/units.hpp"
#include "pbms/velocity_ramp.hpp"

namespace pbms::mpm {
namespace {

// Groups first, then bodies: every body is a group of its own too, after
// the region groups, in the bits of MaterialPoints::groups.
void name_groups(const MpmModelParams& p, MpmModel& m) {
  for (const auto& g : p.groups) {
    if (std::find(m.group_names.begin(), m.group_names.end(), g.name) != m.group_names.end()) {
      throw Error(fmt::format("group '{}' is defined twice", g.name));
    }
    if (m.group_names.size() == 32) throw Error("at most 32 groups per stage");
    m.group_names.push_back(g.name);
  }
  for (const auto& b : p.bodies) {
    if (std::find(m.group_names.begin(), m.group_names.end(), b.name) != m.group_names.end()) {
      throw Error(fmt::format("body '{}' has the name of a group or another body", b.name));
    }
    if (m.group_names.size() == 32) throw Error("at most 32 groups and bodies per stage");
    m.group_names.push_back(b.name);
  }
}

// The body's points, numbered on from `id`, in the groups whose regions
// hold them at the start and in its own (`body_bit`).
void add_body(const BodyParams& b, uint32_t body_bit, const std::vector<GroupParams>& groups,
              const MaterialSet& materials, MpmModel& m, int64_t& id) {
  const auto it = std::find(materials.names.begin(), materials.names.end(), b.material);
  if (it == materials.names.end())
    throw Error(fmt::format("body '{}': unknown material '{}'", b.name, b.material));
  const int mat = static_cast<int>(it - materials.names.begin());
  const grid::Material& model = *materials.models[static_cast<size_t>(mat)];
  auto ppc = b.points_per_cell;
  if (ppc.size() == 1) ppc = {ppc[0], ppc[0], ppc[0]};
  const auto filled = geometry::fill_cells(*b.region, m.grid, {ppc.at(0), ppc.at(1), ppc.at(2)});
  if (filled.positions.empty()) {
    throw Error(fmt::format("body '{}': its region holds no material point of the grid", b.name));
  }
  const grid::MaterialPointState s0 =
      model.initial_state(materials.density[static_cast<size_t>(mat)], b.pressure);
  for (size_t k = 0; k < filled.positions.size(); ++k) {
    const grid::Vec3& x = filled.positions[k];
    uint32_t bits = body_bit;
    for (size_t gi = 0; gi < groups.size(); ++gi) {
      if (groups[gi].region->contains(x)) bits |= 1u << gi;
    }
    m.points.add(id++, x, filled.volumes[k], s0, mat, bits);
    grid::Vec3 v = b.velocity;
    if (b.axial_mode) {
      // First axial mode of a bar fixed at `fixed_end` and free at
      // fixed_end + length: v = A sin(pi s / 2L).
      const AxialMode& mode = *b.axial_mode;
      const size_t a = mode.axis;
      const double sfrac = (x[a] - mode.fixed_end) / mode.length;
      v[a] += mode.amplitude * std::sin(0.5 * std::numbers::pi * sfrac);
    }
    m.points.v.back() = v;
  }
}

void count_group_sizes(MpmModel& m) {
  m.group_sizes.assign(m.group_names.size(), 0);
  for (const uint32_t bits : m.points.groups) {
    for (size_t gi = 0; gi < m.group_names.size(); ++gi) {
      if (bits & (1u << gi)) ++m.group_sizes[gi];
    }
  }
}

// Every node whose position lies in the region.
void add_condition(MpmModel& m, const NodesCondition& c) {
  grid::NodeConstraint nc;
  nc.axis = c.axes;
  if (c.velocity) nc.velocity = *c.velocity;
  std::array<int, 3> lo{}, hi{};
  bool any = false;
  const auto n = m.grid.nodes_per_axis();
  for (int k = 0; k < n[2]; ++k) {
    for (int j = 0; j < n[1]; ++j) {
      for (int i = 0; i < n[0]; ++i) {
        if (!c.region->contains(m.grid.node_position({i, j, k}))) continue;
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
}

void add_condition(MpmModel& m, const GroupVelocityCondition& c) {
  grid::PointVelocity pv;
  pv.group_mask = m.group_mask(c.group);
  pv.axis = c.axes;
  pv.velocity = c.velocity;
  m.point_velocity_ramps.push_back({c.ramp_time, pv.velocity});
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
  m.point_velocity_groups.push_back(c.group);
}

void add_condition(MpmModel& m, const GroupForceCondition& c) {
  grid::PointLoad load;
  load.group_mask = m.group_mask(c.group);
  const auto count = m.group_sizes[static_cast<size_t>(std::countr_zero(load.group_mask))];
  if (count == 0) throw Error(fmt::format("group '{}' has no material point to load", c.group));
  for (size_t a = 0; a < 3; ++a) load.force_per_point[a] = c.force[a] / static_cast<double>(count);
  m.bc.loads.push_back(load);
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

MpmModel build_model(const MpmModelParams& p, MaterialSet& materials) {
  MpmModel m;
  m.metal_units = p.metal_units;
  m.grid = grid::RegularGrid(p.grid.origin, p.grid.cell_size, p.grid.cells);
  m.periodic = p.grid.periodic;
  m.shape_function = p.shape_function;
  m.options = p.options;
  name_groups(p, m);
  int64_t id = 0;
  for (size_t b = 0; b < p.bodies.size(); ++b) {
    const uint32_t body_bit = 1u << (p.groups.size() + b);
    add_body(p.bodies[b], body_bit, p.groups, materials, m, id);
  }
  count_group_sizes(m);
  for (const auto& c : p.boundary) {
    std::visit([&m](const auto& kind) { add_condition(m, kind); }, c);
  }
  m.bc.body_acceleration = p.body_acceleration;
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

std::vector<double> point_velocities_of(const grid::BoundaryConditions& bc) {
  std::vector<double> out;
  for (const auto& pv : bc.point_velocities) {
    out.insert(out.end(), pv.velocity.begin(), pv.velocity.end());
  }
  return out;
}

void restore_point_velocities(grid::BoundaryConditions& bc, const std::vector<double>& v) {
  if (v.size() != 3 * bc.point_velocities.size()) {
    throw Error(fmt::format("MPM: a checkpoint with {} held-group velocities for {} groups",
                            v.size() / 3, bc.point_velocities.size()));
  }
  for (std::size_t k = 0; k < bc.point_velocities.size(); ++k) {
    for (std::size_t a = 0; a < 3; ++a) bc.point_velocities[k].velocity[a] = v[3 * k + a];
  }
}

}  // namespace pbms::mpm
