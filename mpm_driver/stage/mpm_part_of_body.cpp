#include "mpm_part_of_body.hpp"

#include <cmath>

#include "materials/linear_elastic.hpp"
#include "pbms/units.hpp"

namespace pbms::mpm {
namespace {

constexpr std::size_t kRowWidth = 9;  // id, x, v, mass, group bits

// The handed-over points on the shared grid. Rigid and frozen groups with
// points here are held at their velocity, as an MPM grip is.
MpmModel model_of(const coupling::ConcurrentParams& cp, const coupling::Handover& body,
                  const std::vector<std::string>& groups, double volume) {
  MpmModel m;
  m.grid = cp.grid;
  m.periodic = cp.periodic;
  m.options.flip = cp.flip;
  m.options.units = UnitSystem::metal();
  // The DPD part's nodal update skips only empty nodes; the shared nodes
  // must be updated alike.
  m.options.small_mass_fraction = 0.0;
  m.options.ddmp = cp.ddmp;
  m.options.ddmp_face_vanishing = cp.ddmp;
  m.group_names = groups;
  for (std::size_t r = 0; r + kRowWidth <= body.rows.size(); r += kRowWidth) {
    const double* d = &body.rows[r];
    MaterialPointState s;
    s.density = d[7] / volume;
    m.points.add(std::llround(d[0]), {d[1], d[2], d[3]}, volume, s, 0,
                 static_cast<std::uint32_t>(std::llround(d[8])));
    m.points.v.back() = {d[4], d[5], d[6]};
    m.points.mass.back() = d[7];
  }
  for (const auto& h : cp.held) {
    PointVelocity pv;
    pv.group_mask = m.group_mask(h.group);
    pv.axis = {true, true, true};
    pv.velocity = h.ramp_time > 0.0 ? Vec3{0.0, 0.0, 0.0} : h.velocity;
    m.bc.point_velocities.push_back(pv);
    m.point_velocity_ramps.push_back({h.ramp_time, h.velocity});
  }
  return m;
}

}  // namespace

MpmPartOfBody::MpmPartOfBody(MPI_Comm comm, const coupling::ConcurrentParams& cp,
                             const coupling::Handover& body, const YAML::Node& material) {
  const YAML::Node header = YAML::Load(body.header);
  groups_ = header["groups"].as<std::vector<std::string>>();
  const auto lo = header["band_lo"].as<std::vector<int>>();
  const auto hi = header["band_hi"].as<std::vector<int>>();
  band_ = grid::NodeBox{{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
  reach_ = header["reach"].as<double>();
  lattice_constant_ = cp.lattice_constant.value_or(material["lattice_constant"].as<double>());
  const double a = lattice_constant_;
  const double volume = a * a * a / 4.0;  // one fcc site
  MaterialSet materials;
  materials.models.push_back(std::make_unique<LinearElastic>(cp.youngs_modulus, cp.poisson_ratio));
  materials.names.push_back("continuum");
  materials.density.push_back(material["mass"].as<double>() / volume);
  engine_ =
      std::make_unique<MpmEngine>(comm, model_of(cp, body, groups_, volume), std::move(materials));
  side_ = std::make_unique<ConcurrentMpmSide>(*engine_, cp.time_step, header["skin"].as<double>());
  time_step_ = cp.time_step;
}

void MpmPartOfBody::ramp_grips(std::int64_t step) {
  ramp_point_velocities(engine_->model(), engine_->boundary_conditions(), step, time_step_);
}

}  // namespace pbms::mpm
