#include "mpm_solver.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::mpm {
namespace {

inline Vec3 operator*(double s, const Vec3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
inline void add_to(Vec3& a, const Vec3& b) {
  a[0] += b[0];
  a[1] += b[1];
  a[2] += b[2];
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

UnitSystem UnitSystem::metal() {
  return {1.0 / units::kBarPerEvPerA3, 1.0 / units::kMvv2e};
}

MpmSolver::MpmSolver(grid::RegularGrid grid, std::unique_ptr<grid::ShapeFunction> shape,
                     std::vector<std::unique_ptr<Material>> materials, SolverOptions options)
    : grid_(grid), shape_(std::move(shape)), materials_(std::move(materials)), opt_(options) {
  const auto n = static_cast<size_t>(grid_.node_count());
  mass_.assign(n, 0.0);
  momentum_.assign(n, {0.0, 0.0, 0.0});
  force_.assign(n, {0.0, 0.0, 0.0});
  velocity_.assign(n, {0.0, 0.0, 0.0});
}

void MpmSolver::evaluate(const Vec3& x, int64_t id, grid::ShapeStencil& s) const {
  if (!grid_.contains(x)) {
    throw Error(fmt::format("material point {} left the grid at ({:.6g}, {:.6g}, {:.6g})", id, x[0],
                            x[1], x[2]));
  }
  shape_->evaluate(grid_, x, s);
}

double MpmSolver::alpha(const MaterialPoints& points, size_t p) const {
  if (!opt_.ddmp) return 1.0;
  return opt_.ddmp_face_vanishing ? grid::face_vanishing_blend(grid_, points.x[p]) : 0.0;
}

void MpmSolver::map_mass_momentum(const MaterialPoints& points) {
  std::fill(mass_.begin(), mass_.end(), 0.0);
  std::fill(momentum_.begin(), momentum_.end(), Vec3{0.0, 0.0, 0.0});
  grid::ShapeStencil s;
  for (size_t p = 0; p < points.size(); ++p) {
    evaluate(points.x[p], points.id[p], s);
    const double m = points.mass[p];
    for (int k = 0; k < s.count; ++k) {
      const auto i = static_cast<size_t>(s.node[static_cast<size_t>(k)]);
      const double w = s.N[static_cast<size_t>(k)] * m;
      mass_[i] += w;
      add_to(momentum_[i], w * points.v[p]);
    }
  }
}

void MpmSolver::apply_node_constraints(const BoundaryConditions& bc, std::vector<Vec3>& field,
                                       bool is_velocity) const {
  for (const auto& c : bc.nodes) {
    const auto box = c.nodes.intersected(grid_.node_box());
    for (int k = box.lo[2]; k < box.hi[2]; ++k) {
      for (int j = box.lo[1]; j < box.hi[1]; ++j) {
        for (int i = box.lo[0]; i < box.hi[0]; ++i) {
          auto& f = field[static_cast<size_t>(grid_.node_index({i, j, k}))];
          for (int a = 0; a < 3; ++a) {
            if (c.axis[static_cast<size_t>(a)]) {
              f[static_cast<size_t>(a)] = is_velocity ? c.velocity[static_cast<size_t>(a)] : 0.0;
            }
          }
        }
      }
    }
  }
}

void MpmSolver::prepare_ddmp(const MaterialPoints& points) {
  dual_ = std::make_unique<grid::DualDomainOperator>(grid_, *shape_, points.x);
}

void MpmSolver::compute_velocity_gradients(const MaterialPoints& points, std::vector<Mat3>& L) {
  L.assign(points.size(), Mat3::Zero());
  // Dual-domain part: a nodal velocity gradient G_j = sum_i v_i (x) D_ji,
  // interpolated to the points with N (seed Appendix 2's nodal central
  // difference, in 3-D).
  std::vector<Mat3> G;
  if (opt_.ddmp) {
    G.assign(mass_.size(), Mat3::Zero());
    for (size_t j = 0; j < G.size(); ++j) {
      for (const auto& e : dual_->row(static_cast<int64_t>(j))) {
        const auto& v = velocity_[static_cast<size_t>(e.node)];
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b)
            G[j](a, b) += v[static_cast<size_t>(a)] * e.d[static_cast<size_t>(b)];
        }
      }
    }
  }
  grid::ShapeStencil s;
  for (size_t p = 0; p < points.size(); ++p) {
    evaluate(points.x[p], points.id[p], s);
    const double al = alpha(points, p);
    Mat3& Lp = L[p];
    for (int k = 0; k < s.count; ++k) {
      const auto kk = static_cast<size_t>(k);
      const auto& v = velocity_[static_cast<size_t>(s.node[kk])];
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          Lp(a, b) += al * v[static_cast<size_t>(a)] * s.dN[kk][static_cast<size_t>(b)];
        }
      }
      if (opt_.ddmp && al < 1.0) Lp += (1.0 - al) * s.N[kk] * G[static_cast<size_t>(s.node[kk])];
    }
  }
}

void MpmSolver::update_stress(MaterialPoints& points, const std::vector<Mat3>& L, double dt) {
  for (size_t p = 0; p < points.size(); ++p) {
    points.F[p] = (Mat3::Identity() + dt * L[p]) * points.F[p];
    const double J = points.F[p].determinant();
    if (!(J > 0.0)) {
      throw Error(
          fmt::format("material point {} at ({:.6g}, {:.6g}, {:.6g}) inverted "
                      "(det F = {:.3g}): the time step is too large or the material "
                      "failed",
                      points.id[p], points.x[p][0], points.x[p][1], points.x[p][2], J));
    }
    points.state[p].density = points.mass[p] / (points.volume0[p] * J);
    materials_[static_cast<size_t>(points.material[p])]->update(L[p], dt, points.state[p]);
  }
}

void MpmSolver::internal_forces(const MaterialPoints& points) {
  std::fill(force_.begin(), force_.end(), Vec3{0.0, 0.0, 0.0});
  const double k = opt_.units.stress_volume_to_energy;
  std::vector<std::array<double, 6>> S;  // dual-domain nodal stress moments
  if (opt_.ddmp) S.assign(mass_.size(), {0, 0, 0, 0, 0, 0});
  grid::ShapeStencil s;
  for (size_t p = 0; p < points.size(); ++p) {
    evaluate(points.x[p], points.id[p], s);
    const double al = alpha(points, p);
    const auto& sg = points.state[p].stress.voigt;  // xx yy zz yz xz xy
    const double V = points.volume(p) * k;
    for (int q = 0; q < s.count; ++q) {
      const auto qq = static_cast<size_t>(q);
      const auto i = static_cast<size_t>(s.node[qq]);
      const auto& g = s.dN[qq];
      const double w = al * V;
      force_[i][0] -= w * (sg[0] * g[0] + sg[5] * g[1] + sg[4] * g[2]);
      force_[i][1] -= w * (sg[5] * g[0] + sg[1] * g[1] + sg[3] * g[2]);
      force_[i][2] -= w * (sg[4] * g[0] + sg[3] * g[1] + sg[2] * g[2]);
      if (opt_.ddmp && al < 1.0) {
        const double wd = (1.0 - al) * V * s.N[qq];
        for (int c = 0; c < 6; ++c) S[i][static_cast<size_t>(c)] += wd * sg[static_cast<size_t>(c)];
      }
    }
  }
  if (!opt_.ddmp) return;
  for (size_t j = 0; j < S.size(); ++j) {
    const auto& t = S[j];
    if (t == std::array<double, 6>{0, 0, 0, 0, 0, 0}) continue;
    for (const auto& e : dual_->row(static_cast<int64_t>(j))) {
      auto& f = force_[static_cast<size_t>(e.node)];
      const auto& d = e.d;
      f[0] -= t[0] * d[0] + t[5] * d[1] + t[4] * d[2];
      f[1] -= t[5] * d[0] + t[1] * d[1] + t[3] * d[2];
      f[2] -= t[4] * d[0] + t[3] * d[1] + t[2] * d[2];
    }
  }
}

void MpmSolver::step(MaterialPoints& points, const BoundaryConditions& bc, double dt) {
  const size_t n = points.size();
  if (n == 0) return;
  mass_floor_ =
      *std::min_element(points.mass.begin(), points.mass.end()) * opt_.small_mass_fraction;
  const double kf = opt_.units.force_per_mass_to_accel;

  map_mass_momentum(points);
  if (opt_.ddmp) prepare_ddmp(points);
  auto nodal_velocity_from_momentum = [&] {
    for (size_t i = 0; i < mass_.size(); ++i) {
      velocity_[i] = mass_[i] > mass_floor_ ? (1.0 / mass_[i]) * momentum_[i] : Vec3{0, 0, 0};
    }
    apply_node_constraints(bc, velocity_, true);
  };
  if (opt_.stress_update == StressUpdate::kFirst) {
    nodal_velocity_from_momentum();
    compute_velocity_gradients(points, L_);
    update_stress(points, L_, dt);
  }

  internal_forces(points);
  grid::ShapeStencil s;
  const bool body = dot(bc.body_acceleration, bc.body_acceleration) > 0.0;
  if (body) {
    for (size_t p = 0; p < n; ++p) {
      evaluate(points.x[p], points.id[p], s);
      const Vec3 fb = (points.mass[p] / kf) * bc.body_acceleration;
      for (int q = 0; q < s.count; ++q) {
        add_to(force_[static_cast<size_t>(s.node[static_cast<size_t>(q)])],
               s.N[static_cast<size_t>(q)] * fb);
      }
    }
  }
  for (const auto& load : bc.loads) {
    if (load.points.empty()) continue;
    const Vec3 share = (1.0 / static_cast<double>(load.points.size())) * load.total_force;
    for (size_t p : load.points) {
      evaluate(points.x[p], points.id[p], s);
      for (int q = 0; q < s.count; ++q) {
        add_to(force_[static_cast<size_t>(s.node[static_cast<size_t>(q)])],
               s.N[static_cast<size_t>(q)] * share);
      }
    }
  }

  // Nodal update. `force_` becomes the nodal acceleration, and `velocity_`
  // the end-of-step velocity; constrained components are imposed on both so
  // that FLIP and PIC agree with the constraint.
  std::vector<Vec3> v_old(mass_.size());
  for (size_t i = 0; i < mass_.size(); ++i) {
    if (mass_[i] > mass_floor_) {
      v_old[i] = (1.0 / mass_[i]) * momentum_[i];
      force_[i] = (kf / mass_[i]) * force_[i];
      velocity_[i] = v_old[i];
      add_to(velocity_[i], dt * force_[i]);
    } else {
      v_old[i] = force_[i] = velocity_[i] = {0.0, 0.0, 0.0};
    }
  }
  apply_node_constraints(bc, velocity_, true);
  for (size_t i = 0; i < mass_.size(); ++i) {
    if (mass_[i] > mass_floor_) {
      for (int a = 0; a < 3; ++a) {
        const auto aa = static_cast<size_t>(a);
        force_[i][aa] = (velocity_[i][aa] - v_old[i][aa]) / dt;
      }
    }
  }

  // Grid to points: velocities by the FLIP/PIC blend, positions with the
  // nodal velocity field (s-7, s-8).
  std::vector<Vec3> x_old = points.x;
  for (size_t p = 0; p < n; ++p) {
    evaluate(points.x[p], points.id[p], s);
    Vec3 acc{0, 0, 0}, vel{0, 0, 0};
    for (int q = 0; q < s.count; ++q) {
      const auto qq = static_cast<size_t>(q);
      const auto i = static_cast<size_t>(s.node[qq]);
      add_to(acc, s.N[qq] * force_[i]);
      add_to(vel, s.N[qq] * velocity_[i]);
    }
    Vec3 flip = points.v[p];
    add_to(flip, dt * acc);
    for (int a = 0; a < 3; ++a) {
      const auto aa = static_cast<size_t>(a);
      points.v[p][aa] = opt_.flip * flip[aa] + (1.0 - opt_.flip) * vel[aa];
    }
    add_to(points.x[p], dt * vel);
  }
  for (const auto& pv : bc.point_velocities) {
    for (size_t p : pv.points) {
      for (int a = 0; a < 3; ++a) {
        if (pv.axis[static_cast<size_t>(a)])
          points.v[p][static_cast<size_t>(a)] = pv.velocity[static_cast<size_t>(a)];
      }
    }
  }

  if (opt_.stress_update == StressUpdate::kLast) {
    // Remap the updated point momenta to the grid with the shape functions
    // of this step (s-10, s-11), then the stress update (s-12 to s-14).
    std::swap(points.x, x_old);
    map_mass_momentum(points);
    nodal_velocity_from_momentum();
    compute_velocity_gradients(points, L_);
    std::swap(points.x, x_old);
    update_stress(points, L_, dt);
  }
  for (size_t p = 0; p < n; ++p) {
    if (!grid_.contains(points.x[p])) {
      throw Error(fmt::format("material point {} left the grid at ({:.6g}, {:.6g}, {:.6g})",
                              points.id[p], points.x[p][0], points.x[p][1], points.x[p][2]));
    }
  }
}

double MpmSolver::stable_time_step(const MaterialPoints& points) const {
  const double to_speed =
      std::sqrt(opt_.units.stress_volume_to_energy * opt_.units.force_per_mass_to_accel);
  double cmax = 0.0;
  for (size_t p = 0; p < points.size(); ++p) {
    const double c =
        materials_[static_cast<size_t>(points.material[p])]->wave_speed(points.state[p]) * to_speed;
    cmax = std::max(cmax, c + std::sqrt(dot(points.v[p], points.v[p])));
  }
  return cmax > 0.0 ? grid_.cell_size() / cmax : INFINITY;
}

EnergySummary MpmSolver::energy(const MaterialPoints& points) const {
  EnergySummary e;
  const double kf = opt_.units.force_per_mass_to_accel;
  const double ks = opt_.units.stress_volume_to_energy;
  for (size_t p = 0; p < points.size(); ++p) {
    const auto& m = *materials_[static_cast<size_t>(points.material[p])];
    e.kinetic += 0.5 * points.mass[p] * dot(points.v[p], points.v[p]) / kf;
    const double V = points.volume(p) * ks;
    e.stored += V * m.stored_energy_density(points.state[p]);
    e.dissipated += V * m.dissipated_energy_density(points.state[p]);
  }
  return e;
}

}  // namespace pbms::mpm
