#include "mpm_part_of_body.hpp"

#include <cmath>

#include "materials/linear_elastic.hpp"
#include "pbms/units.hpp"

namespace pbms::mpm {
namespace {

// The handed-over points on the shared grid. Rigid and frozen groups with
// points here are held at their velocity, as an MPM grip is.
MpmModel model_of(const coupling::ConcurrentParams& cp, const coupling::BodyHandover& body,
                  double volume) {
  MpmModel m;
  m.grid = cp.grid;
  m.periodic = cp.periodic;
  m.options.flip = cp.flip;
  m.options.units = grid::UnitSystem::metal();
  // The DPD part's nodal update skips only empty nodes; the shared nodes
  // must be updated alike.
  m.options.small_mass_fraction = 0.0;
  m.options.ddmp = cp.ddmp;
  m.options.ddmp_face_vanishing = cp.ddmp;
  m.group_names = body.groups;
  for (const auto& p : body.points) {
    grid::MaterialPointState s;
    s.density = p.mass / volume;
    m.points.add(p.id, p.x, volume, s, 0, p.groups);
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
  return m;
}

}  // namespace

MpmPartOfBody::MpmPartOfBody(MPI_Comm comm, const coupling::ConcurrentParams& cp,
                             const coupling::BodyHandover& body) {
  groups_ = body.groups;
  band_ = body.band();
  reach_ = body.reach;
  lattice_constant_ = cp.point_lattice_constant();
  const double a = lattice_constant_;
  const double volume = a * a * a / 4.0;  // one fcc site
  MaterialSet materials;
  materials.models.push_back(std::make_unique<LinearElastic>(cp.youngs_modulus, cp.poisson_ratio));
  materials.names.push_back("continuum");
  materials.density.push_back(cp.particle_mass / volume);
  engine_ = std::make_unique<MpmEngine>(comm, model_of(cp, body, volume), std::move(materials));
  side_ = std::make_unique<ConcurrentMpmSide>(*engine_, cp.time_step, body.skin);
  time_step_ = cp.time_step;
}

void MpmPartOfBody::ramp_grips(std::int64_t step) {
  ramp_point_velocities(engine_->model(), engine_->boundary_conditions(), step, time_step_);
}

}  // namespace pbms::mpm
