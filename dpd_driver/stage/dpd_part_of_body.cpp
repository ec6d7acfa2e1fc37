#include "dpd_part_of_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/fcc_crystal.hpp"
#include "kernels/periodic_wrap.hpp"
#include "pbms/coupling/gas_lattice.hpp"
#include "properties/elastic_constants.hpp"

namespace pbms::dpd {
namespace {

using coupling::ConcurrentParams;
using coupling::Solver;

struct SplitBody {
  DpdParticles dpd;
  std::vector<coupling::HandedPoint> mpm;
};

SplitBody split_body(const DpdParticles& all, const ConcurrentParams& cp) {
  SplitBody s;
  s.dpd.mass_per_type = all.mass_per_type;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (cp.solver_at(all.x[i]) == Solver::kMpm) {
      s.mpm.push_back({all.id[i], all.x[i], all.v[i], all.mass(i), all.group_mask[i]});
      continue;
    }
    s.dpd.add(all.id[i], all.type[i], all.x[i], all.v[i]);
    s.dpd.image.back() = all.image[i];
    s.dpd.internal_energy.back() = all.internal_energy[i];
    s.dpd.group_mask.back() = all.group_mask[i];
  }
  return s;
}

// The body uniformly strained (initial_strain): every position scaled
// about the box's lower corner, the MPM part's as the DPD part's.
void strain_body(SplitBody& body, const ConcurrentParams& cp, const geometry::Box& box) {
  const auto scale = [&](Vec3& x) {
    for (std::size_t a = 0; a < 3; ++a)
      x[a] = box.lo[a] + (1.0 + cp.initial_strain[a]) * (x[a] - box.lo[a]);
  };
  for (auto& x : body.dpd.x) scale(x);
  for (auto& p : body.mpm) scale(p.x);
}

// The stress an initial_strain puts in the body's crystal, bar, Voigt
// [xx, yy, zz, yz, xz, xy]: the static stress of the perfect periodic
// lattice strained, less that of it unstrained (whose part the ghost-force
// correction's reference state holds). Exact at 0 K, where the MPM points
// then start as the crystal they replace; a linear continuum's C:ε would
// miss its nonlinearity (7 % of the stress at 1 % isotropic strain).
std::array<double, 6> strained_lattice_stress(PairStyle& pair, const ConcurrentParams& cp) {
  const auto& e = cp.initial_strain;
  if (e == std::array<double, 3>{0.0, 0.0, 0.0}) return {};
  const double a = cp.point_lattice_constant();
  const ThermalSettings at_rest;  // temperature 0: the static stress
  const int cells =
      static_cast<int>(std::ceil(2.0 * sampling_neighbour_reach(pair, at_rest, a) / a)) + 1;
  const auto stress_of = [&](const std::array<double, 3>& strain) {
    FccCrystal c = fcc_crystal(cells, cells, cells, a, cp.particle_mass);
    for (std::size_t k = 0; k < 3; ++k) {
      for (auto& x : c.particles.x) x[k] *= 1.0 + strain[k];
      c.box.hi[k] = c.box.lo[k] + (1.0 + strain[k]) * c.box.length(static_cast<int>(k));
    }
    return sample_stress(pair, std::move(c), at_rest, a).front();  // GPa, xx yy zz xy xz yz
  };
  const auto strained = stress_of(e), unstrained = stress_of({0.0, 0.0, 0.0});
  constexpr double kBarPerGpa = 1.0e4;
  std::array<double, 6> s{};
  const std::array<std::size_t, 6> from{0, 1, 2, 5, 4, 3};
  for (std::size_t k = 0; k < 6; ++k) s[k] = kBarPerGpa * (strained[from[k]] - unstrained[from[k]]);
  return s;
}

// The gas around the body (gas_sites), after the body's own points, its
// ids after the body's, at rest.
void add_gas(SplitBody& body, const ConcurrentParams& cp, const geometry::Box& box) {
  const coupling::GasParams& gas = *cp.gas;
  std::vector<Vec3> solid = body.dpd.x;
  std::int64_t next_id = 0;
  for (const auto id : body.dpd.id) next_id = std::max(next_id, id + 1);
  for (const auto& p : body.mpm) {
    solid.push_back(p.x);
    next_id = std::max(next_id, p.id + 1);
  }
  const std::vector<Vec3> sites =
      coupling::gas_sites(gas, box, cp.periodic, solid, cp.material_lattice_constant);
  const std::vector<bool> near = coupling::near_body(sites, solid, gas.probe_distance);
  for (std::size_t s = 0; s < sites.size(); ++s) {
    coupling::HandedPoint p{next_id++, sites[s], {0.0, 0.0, 0.0}, gas.point_mass(), 0};
    p.kind = static_cast<std::uint32_t>(near[s] ? coupling::HandedKind::kGas
                                                : coupling::HandedKind::kGasAway);
    body.mpm.push_back(p);
  }
}

// The cells a set of positions touches, grown by `margin`, as nodes.
grid::NodeBox nodes_around(const std::vector<Vec3>& x, const grid::RegularGrid& g, double margin) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  for (const auto& p : x) {
    for (std::size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  grid::NodeBox b;
  if (x.empty()) return b;
  for (std::size_t a = 0; a < 3; ++a) {
    b.lo[a] = static_cast<int>(std::floor((lo[a] - margin - g.origin()[a]) / g.cell_size()));
    b.hi[a] = static_cast<int>(std::floor((hi[a] + margin - g.origin()[a]) / g.cell_size())) + 2;
  }
  return b.intersected(g.node_box());
}

// The nodes both parts may deposit on. On periodic axes the whole axis:
// the plan folds images onto their owners.
grid::NodeBox interface_band(const SplitBody& body, const ConcurrentParams& cp, double reach) {
  std::vector<Vec3> mpm;
  for (const auto& p : body.mpm) mpm.push_back(p.x);
  const double margin = cp.band_margin + reach;
  grid::NodeBox band =
      nodes_around(body.dpd.x, cp.grid, margin).intersected(nodes_around(mpm, cp.grid, margin));
  for (std::size_t a = 0; a < 3; ++a) {
    if (cp.periodic[a] && !band.empty()) {
      band.lo[a] = 0;
      band.hi[a] = cp.grid.cells()[a] + 1;
    }
  }
  return band;
}

DpdGridSettings grid_settings(const ConcurrentParams& cp, const DpdModel& model) {
  DpdGridSettings s;
  s.cell_size = cp.grid.cell_size();
  s.flip = cp.flip;
  s.move = cp.move;
  s.contact = cp.fields() == coupling::GridFields::kFrictionlessContact;
  for (const auto& m : model.group_motions) s.rigid.push_back({m.mask, m.velocity, m.free_body});
  return s;
}

// Outermost sites plus half a plane spacing on each side (an fcc crystal
// of n cells spans n a).
double extent_along(const DpdParticles& all, std::size_t axis, double plane) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& x : all.x) {
    lo = std::min(lo, x[axis]);
    hi = std::max(hi, x[axis]);
  }
  return hi - lo + plane;
}

}  // namespace

DpdPartOfBody::DpdPartOfBody(MPI_Comm comm, const YAML::Node& params, const YAML::Node& material,
                             std::uint64_t seed, const std::string& stage)
    : cp_(coupling::ConcurrentParams::from_yaml(params, material)),
      model_(build_dpd_model(DpdStageParams::from_yaml(params),
                             MesoparticleMaterial::from_yaml(material),
                             stage_seed(seed, cp_.noise_of.value_or(stage)), stage)) {
  // A state from an earlier stage may lie a little outside the box on a
  // periodic axis (positions wrap at list builds only); the regions see it
  // inside.
  wrap_periodic_axes(model_.particles, model_.box, model_.particles.size());
  const double plane = 0.5 * cp_.material_lattice_constant;
  for (std::size_t a = 0; a < 3; ++a) extent_[a] = extent_along(model_.particles, a, plane);
  const double a0 = cp_.point_lattice_constant();
  nominal_volume_ = static_cast<double>(model_.particles.size()) * a0 * a0 * a0 / 4.0;
  SplitBody body = split_body(model_.particles, cp_);
  model_.particles = DpdParticles{};  // now in `body`
  strain_body(body, cp_, {model_.box.lo, model_.box.hi});
  mpm_count_ = static_cast<double>(body.mpm.size());
  if (cp_.gas) add_gas(body, cp_, {model_.box.lo, model_.box.hi});
  // Partners within the list's reach, chosen afresh when either side has
  // moved half the skin.
  reach_ = std::max(model_.pair->cutoff(), model_.settings.friction.cutoff) + model_.settings.skin;
  band_ = interface_band(body, cp_, reach_);
  dpd_count_ = static_cast<double>(body.dpd.size());
  handover_ = {model_.group_names,   band_.lo,           band_.hi, reach_,
               model_.settings.skin, std::move(body.mpm)};
  handover_.initial_stress = strained_lattice_stress(*model_.pair, cp_);
  engine_ = std::make_unique<DpdEngine>(comm, model_.box, std::move(model_.pair), model_.settings,
                                        std::move(body.dpd));
  engine_->set_prescribed_groups(model_.prescribed_mask);
  engine_->set_rigid_bodies(model_.rigid_bodies);
  grid_ =
      std::make_unique<DpdGridStep>(*engine_, grid_settings(cp_, model_), cp_.grid, cp_.periodic);
  side_ = std::make_unique<ConcurrentDpdSide>(*engine_, *grid_, 0);
}

void DpdPartOfBody::ramp_grips(std::int64_t step) {
  for (const auto& r : ramped_velocities(model_.group_motions, step, cp_.time_step)) {
    grid_->set_rigid_velocity(r.mask, r.velocity);
  }
}

}  // namespace pbms::dpd
