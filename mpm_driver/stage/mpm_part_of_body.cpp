#include "mpm_part_of_body.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "materials/ideal_gas.hpp"
#include "materials/linear_elastic.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::mpm {
namespace {

// The names of the part's materials, in the order of their indices.
constexpr const char* kContinuum = "continuum";
constexpr const char* kGas = "gas";

// The non-periodic faces of the grid, which hold the gas in: their nodes
// keep no velocity normal to them. Only mpm_driver holds them, so the nodes
// both programs share (the band) must stay off them.
void add_walls(MpmModel& m, const grid::NodeBox& band) {
  const grid::NodeBox all = m.grid.node_box();
  for (std::size_t a = 0; a < 3; ++a) {
    if (m.periodic[a]) continue;
    if (!band.empty() && (band.lo[a] <= all.lo[a] || band.hi[a] >= all.hi[a])) {
      throw Error(
          fmt::format("gas: the body comes within the interface band's reach of the walls along {} "
                      "(band nodes {}..{} of {}): give the gas more room or lower grid.band_margin",
                      "xyz"[a], band.lo[a], band.hi[a] - 1, all.hi[a] - 1));
    }
    for (const int plane : {all.lo[a], all.hi[a] - 1}) {
      grid::NodeConstraint wall;
      wall.nodes = all;
      wall.nodes.lo[a] = plane;
      wall.nodes.hi[a] = plane + 1;
      wall.axis[a] = true;
      m.bc.nodes.push_back(wall);
    }
  }
}

}  // namespace

MpmModel MpmPartOfBody::model_of(const coupling::ConcurrentParams& cp,
                                 const coupling::BodyHandover& body) const {
  MpmModel m;
  m.grid = cp.grid;
  m.periodic = cp.periodic;
  m.options.flip = cp.flip;
  m.options.move = cp.move;
  m.options.units = grid::UnitSystem::metal();
  // The DPD part's nodal update skips only empty nodes; the shared nodes
  // must be updated alike.
  m.options.small_mass_fraction = 0.0;
  m.options.ddmp = cp.ddmp;
  m.options.ddmp_face_vanishing = cp.ddmp;
  if (cp.fields() == coupling::GridFields::kFrictionlessContact) {
    m.options.contact = grid::ContactField::kSurfaceFromOwnMass;  // the gas's
  }
  const double a = lattice_constant_;
  const double site_volume = a * a * a / 4.0;  // one fcc site
  const double site_density = cp.particle_mass / site_volume;
  m.group_names = body.groups;
  if (cp.gas) {
    m.group_names.emplace_back(kGasAwayGroup);
    m.options.material_flip.assign(static_cast<std::size_t>(gas_) + 1, 1.0);
    m.options.material_flip[static_cast<std::size_t>(gas_)] = cp.gas->flip;
    m.options.material_nouns.assign(static_cast<std::size_t>(gas_) + 1, "");
    m.options.material_nouns[static_cast<std::size_t>(gas_)] = "gas point";
    if (cp.gas->density_from_grid) {
      m.options.material_density_from_grid.assign(static_cast<std::size_t>(gas_) + 1, 0);
      m.options.material_density_from_grid[static_cast<std::size_t>(gas_)] = 1;
      m.options.filler_density = site_density;  // the body's crystal
      m.options.grid_density_weight = std::min(1.0, cp.time_step / cp.gas->density_time);
    }
  }
  const auto& e = cp.initial_strain;
  const double strained_volume = site_volume * (1.0 + e[0]) * (1.0 + e[1]) * (1.0 + e[2]);
  const grid::SymmetricTensor strained_stress{body.initial_stress};
  for (const auto& p : body.points) {
    grid::MaterialPointState s;
    double volume = site_volume;
    int material = continuum_;
    std::uint32_t groups = p.groups;
    if (p.is_gas()) {
      volume = cp.gas->point_volume();
      material = gas_;
      // A ramped gas starts cold, at zero pressure (hold_gas_temperature).
      s = gas_model_->initial_state(p.mass / volume,
                                    cp.gas->ramp_time > 0.0 ? 0.0 : cp.gas->pressure);
      if (p.kind == static_cast<std::uint32_t>(coupling::HandedKind::kGasAway)) {
        groups |= m.group_mask(kGasAwayGroup);
      }
    } else {
      if (continuum_ < 0) throw Error("the MPM part was handed a body site but has no continuum");
      volume = strained_volume;
      s.stress = strained_stress;
      s.density = p.mass / volume;
    }
    m.points.add(p.id, p.x, volume, s, material, groups);
    m.points.v.back() = p.v;
    m.points.mass.back() = p.mass;
  }
  for (const auto& h : cp.held) {
    grid::PointVelocity pv;
    pv.group_mask = m.group_mask(h.group);
    pv.axis = {true, true, true};
    pv.velocity = h.ramp_time > 0.0 ? grid::Vec3{0.0, 0.0, 0.0} : h.velocity;
    m.bc.point_velocities.push_back(pv);
    m.point_velocity_ramps.push_back({h.ramp_time, h.velocity});
  }
  if (cp.gas && cp.gas->walls) add_walls(m, band_);
  return m;
}

MpmPartOfBody::MpmPartOfBody(MPI_Comm comm, const coupling::ConcurrentParams& cp,
                             const coupling::BodyHandover& body) {
  groups_ = body.groups;
  band_ = body.band();
  reach_ = body.reach;
  lattice_constant_ = cp.point_lattice_constant();
  const double a = lattice_constant_;
  MaterialSet materials;
  if (cp.youngs_modulus > 0.0) {
    continuum_ = static_cast<int>(materials.models.size());
    materials.models.push_back(
        std::make_unique<LinearElastic>(cp.youngs_modulus, cp.poisson_ratio));
    materials.names.emplace_back(kContinuum);
    materials.density.push_back(4.0 * cp.particle_mass / (a * a * a));
  }
  if (cp.gas) {
    gas_ = static_cast<int>(materials.models.size());
    auto gas = std::make_unique<IdealGas>(cp.gas->gamma);
    gas_model_ = gas.get();
    materials.models.push_back(std::move(gas));
    materials.names.emplace_back(kGas);
    materials.density.push_back(cp.gas->density);
    gas_energy_ = gas_model_->initial_state(cp.gas->density, cp.gas->pressure).internal_energy;
    if (cp.gas->heat_bath_time > 0.0) gas_relaxation_ = cp.time_step / cp.gas->heat_bath_time;
    gas_ramp_steps_ = cp.gas->ramp_time / cp.time_step;
  }
  engine_ = std::make_unique<MpmEngine>(comm, model_of(cp, body), std::move(materials));
  side_ = std::make_unique<ConcurrentMpmSide>(*engine_, cp.time_step, body.skin, gas_);
  time_step_ = cp.time_step;
}

void MpmPartOfBody::hold_gas_temperature(std::int64_t step) {
  if (!(gas_relaxation_ > 0.0)) return;
  // The ramp's target is a function of the step alone, so that a resumed
  // run goes on where it stopped.
  const double target =
      gas_ramp_steps_ > 0.0
          ? gas_energy_ * std::min(1.0, static_cast<double>(step) / gas_ramp_steps_)
          : gas_energy_;
  grid::MaterialPoints& p = engine_->points();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] != gas_) continue;
    grid::MaterialPointState& s = p.state[i];
    s.internal_energy += gas_relaxation_ * (target - s.internal_energy);
    s.stress =
        grid::SymmetricTensor::isotropic(-gas_model_->pressure(s.density, s.internal_energy));
  }
}

void MpmPartOfBody::ramp_grips(std::int64_t step) {
  ramp_point_velocities(engine_->model(), engine_->boundary_conditions(), step, time_step_);
}

}  // namespace pbms::mpm
