#include "mpm_solver.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/grid/shape_function_linear.hpp"
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
inline void add_scaled(Vec3& a, double s, const Vec3& b) {
  a[0] += s * b[0];
  a[1] += s * b[1];
  a[2] += s * b[2];
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

grid::RegularGrid patch_grid(const GridPatch& patch) {
  const auto& d = patch.domain;
  const auto e = patch.nodes.extent();
  if (patch.nodes.empty() || e[0] < 2 || e[1] < 2 || e[2] < 2 ||
      !(patch.nodes.intersected(d.node_box()) == patch.nodes)) {
    throw Error("MPM solver: the patch must be a box of at least one cell inside the grid");
  }
  std::array<double, 3> origin{};
  for (size_t a = 0; a < 3; ++a) origin[a] = d.origin()[a] + patch.nodes.lo[a] * d.cell_size();
  return grid::RegularGrid(origin, d.cell_size(), {e[0] - 1, e[1] - 1, e[2] - 1});
}

// Shape-function evaluation for the particle passes. The generic one goes
// through the style's virtual evaluate(); the linear one is chosen once per
// step and inlines a fixed 8-node stencil. Both leave the inside check to
// the caller.
// The generic one fills one buffer and returns it; the linear one returns
// its stencil by value, which after inlining lives in registers and drops
// what a pass does not read (the gradients in the G2P pass).
struct GenericEval {
  const grid::ShapeFunction& shape;
  const grid::RegularGrid& grid;
  mutable grid::ShapeStencil buffer;
  const grid::ShapeStencil& operator()(const Vec3& x) const {
    shape.evaluate(grid, x, buffer);
    return buffer;
  }
};

struct LinearEval {
  grid::ShapeFunctionLinear::Kernel kernel;
  grid::LinearStencil operator()(const Vec3& x) const {
    grid::LinearStencil s;
    kernel(x, s);
    return s;
  }
};

}  // namespace

UnitSystem UnitSystem::metal() {
  return {1.0 / units::kBarPerEvPerA3, 1.0 / units::kMvv2e};
}

MpmSolver::MpmSolver(GridPatch patch, std::unique_ptr<grid::ShapeFunction> shape,
                     std::vector<std::unique_ptr<Material>> materials, SolverOptions options)
    : patch_(std::move(patch)),
      local_(patch_grid(patch_)),
      shape_(std::move(shape)),
      materials_(std::move(materials)),
      opt_(options) {
  if (opt_.ddmp && (patch_.sum_shared || patch_.nodes != patch_.domain.node_box())) {
    // The dual-domain operator needs nodal volumes and neighbouring nodal
    // gradients across box faces, which the halo exchange does not carry.
    throw Error(
        "DDMP gradients need the whole, non-periodic grid on one rank: run the mpm_driver "
        "with 1 rank, or use plain gradients");
  }
  const auto n = static_cast<size_t>(local_.node_count());
  node_.assign(n, {});
  velocity_.assign(n, {0.0, 0.0, 0.0});
  acceleration_.assign(n, {0.0, 0.0, 0.0});
  remap_velocity_.assign(n, {0.0, 0.0, 0.0});
  node_force_.assign(n, {0.0, 0.0, 0.0});
  // A node is counted by one rank only: the one whose cells have it as a
  // lower corner, or the last box on a non-periodic upper face.
  unique_node_.assign(n, 0);
  const auto& d = patch_.domain;
  for (std::int64_t li = 0; li < static_cast<std::int64_t>(n); ++li) {
    const auto ijk = patch_.nodes.ijk_of_local(li);
    bool unique = true;
    for (size_t a = 0; a < 3; ++a) {
      const bool last_in_box = ijk[a] == patch_.nodes.hi[a] - 1;
      const bool grid_face = ijk[a] == d.cells()[a];
      if (last_in_box && (patch_.periodic[a] || !grid_face)) unique = false;
    }
    unique_node_[static_cast<size_t>(li)] = unique ? 1 : 0;
  }
}

void MpmSolver::evaluate(const MaterialPoints& points, size_t p, grid::ShapeStencil& s) const {
  const Vec3& x = points.x[p];
  if (!local_.contains(x)) {
    throw Error(fmt::format(
        "material point {} at ({:.6g}, {:.6g}, {:.6g}) is outside {}", points.id[p], x[0], x[1],
        x[2], patch_.domain.contains(x) ? "this rank's box of the grid" : "the grid"));
  }
  shape_->evaluate(local_, x, s);
}

// RegularGrid::contains, inline; NaN compares as outside.
[[gnu::always_inline]] inline bool MpmSolver::inside(const Vec3& x) const {
  const auto& lo = local_.origin();
  const auto& hi = local_.upper();
  return x[0] >= lo[0] && x[0] <= hi[0] && x[1] >= lo[1] && x[1] <= hi[1] && x[2] >= lo[2] &&
         x[2] <= hi[2];
}

template <class Eval>
[[gnu::always_inline]] inline decltype(auto) MpmSolver::locate(const Eval& eval,
                                                               const MaterialPoints& points,
                                                               size_t p) const {
  if (!inside(points.x[p])) [[unlikely]] {
    grid::ShapeStencil unused;
    evaluate(points, p, unused);  // throws, naming the point
  }
  return eval(points.x[p]);
}

double MpmSolver::alpha(const MaterialPoints& points, size_t p) const {
  if (!opt_.ddmp) return 1.0;
  return opt_.ddmp_face_vanishing ? grid::face_vanishing_blend(local_, points.x[p]) : 0.0;
}

void MpmSolver::sum_shared(double* first, int components) {
  if (patch_.sum_shared) patch_.sum_shared(first, components, 7);
}

// Mass, and optionally momentum and the internal and external forces, of
// every point to its nodes (s-1 to s-4). The forces use the stress the
// points carry now, which under update-stress-last is the previous step's.
template <class Eval>
void MpmSolver::scatter(const Eval& eval, const MaterialPoints& points,
                        const BoundaryConditions& bc, bool momentum, bool force) {
  std::fill(node_.begin(), node_.end(), NodeSums{});
  rigid_.assign(bc.point_velocities.size(), std::vector<double>(node_.size(), 0.0));
  const bool dual = force && opt_.ddmp;
  if (dual) S_.assign(node_.size(), {0, 0, 0, 0, 0, 0});
  const double kv = opt_.units.stress_volume_to_energy;
  const double kf = opt_.units.force_per_mass_to_accel;
  const bool body = dot(bc.body_acceleration, bc.body_acceleration) > 0.0;
  if (momentum && force && !dual && !body && bc.loads.empty() && bc.point_velocities.empty()) {
    // The common case without external forces, rigid groups or DDMP: the
    // loop below with its rarely taken branches left out (alpha is 1 and
    // the external force 0).
    for (size_t p = 0; p < points.size(); ++p) {
      const auto& s = locate(eval, points, p);
      const double m = points.mass[p];
      const Vec3& v = points.v[p];
      const double w = points.volume(p) * kv;
      const auto& t = points.state[p].stress.voigt;  // xx yy zz yz xz xy
      for (int q = 0; q < s.count; ++q) {
        const auto qq = static_cast<size_t>(q);
        NodeSums& nd = node_[static_cast<size_t>(s.node[qq])];
        const double Nm = s.N[qq] * m;
        nd.mass += Nm;
        add_scaled(nd.momentum, Nm, v);
        const auto& g = s.dN[qq];
        nd.force[0] -= w * (t[0] * g[0] + t[5] * g[1] + t[4] * g[2]);
        nd.force[1] -= w * (t[5] * g[0] + t[1] * g[1] + t[3] * g[2]);
        nd.force[2] -= w * (t[4] * g[0] + t[3] * g[1] + t[2] * g[2]);
      }
    }
    return;
  }
  for (size_t p = 0; p < points.size(); ++p) {
    const auto& s = locate(eval, points, p);
    const double m = points.mass[p];
    const Vec3& v = points.v[p];
    Vec3 fext{0.0, 0.0, 0.0};
    double V = 0.0, al = 1.0;
    const std::array<double, 6>* sg = nullptr;
    if (force) {
      if (body) fext = (m / kf) * bc.body_acceleration;
      for (const auto& load : bc.loads) {
        if (points.in_group(p, load.group_mask)) add_to(fext, load.force_per_point);
      }
      V = points.volume(p) * kv;
      al = alpha(points, p);
      sg = &points.state[p].stress.voigt;  // xx yy zz yz xz xy
    }
    for (size_t c = 0; c < bc.point_velocities.size(); ++c) {
      if (!points.in_group(p, bc.point_velocities[c].group_mask)) continue;
      for (int q = 0; q < s.count; ++q) {
        const auto qq = static_cast<size_t>(q);
        if (s.N[qq] > 0.0) rigid_[c][static_cast<size_t>(s.node[qq])] += s.N[qq];
      }
    }
    for (int q = 0; q < s.count; ++q) {
      const auto qq = static_cast<size_t>(q);
      NodeSums& nd = node_[static_cast<size_t>(s.node[qq])];
      const double N = s.N[qq];
      nd.mass += N * m;
      if (momentum) add_scaled(nd.momentum, N * m, v);
      if (!force) continue;
      const auto& t = *sg;
      const auto& g = s.dN[qq];
      const double w = al * V;
      nd.force[0] += N * fext[0] - w * (t[0] * g[0] + t[5] * g[1] + t[4] * g[2]);
      nd.force[1] += N * fext[1] - w * (t[5] * g[0] + t[1] * g[1] + t[3] * g[2]);
      nd.force[2] += N * fext[2] - w * (t[4] * g[0] + t[3] * g[1] + t[2] * g[2]);
      if (dual && al < 1.0) {
        auto& S = S_[static_cast<size_t>(s.node[qq])];
        const double wd = (1.0 - al) * V * N;
        for (size_t c = 0; c < 6; ++c) S[c] += wd * t[c];
      }
    }
  }
  if (!dual) return;
  // Dual-domain part of the internal force: nodal stress moments spread
  // with the operator's rows D_ji.
  for (size_t j = 0; j < S_.size(); ++j) {
    const auto& t = S_[j];
    if (t == std::array<double, 6>{0, 0, 0, 0, 0, 0}) continue;
    for (const auto& e : dual_->row(static_cast<int64_t>(j))) {
      auto& f = node_[static_cast<size_t>(e.node)].force;
      const auto& d = e.d;
      f[0] -= t[0] * d[0] + t[5] * d[1] + t[4] * d[2];
      f[1] -= t[5] * d[0] + t[1] * d[1] + t[3] * d[2];
      f[2] -= t[4] * d[0] + t[3] * d[1] + t[2] * d[2];
    }
  }
}

void MpmSolver::apply_node_constraints(const BoundaryConditions& bc, std::vector<Vec3>& field,
                                       bool is_velocity) const {
  for (const auto& c : bc.nodes) {
    const auto box = c.nodes.intersected(patch_.nodes);
    for (int k = box.lo[2]; k < box.hi[2]; ++k) {
      for (int j = box.lo[1]; j < box.hi[1]; ++j) {
        for (int i = box.lo[0]; i < box.hi[0]; ++i) {
          auto& f = field[static_cast<size_t>(patch_.nodes.local_index({i, j, k}))];
          for (size_t a = 0; a < 3; ++a) {
            if (c.axis[a]) f[a] = is_velocity ? c.velocity[a] : 0.0;
          }
        }
      }
    }
  }
}

void MpmSolver::nodal_velocities(const BoundaryConditions& bc, std::vector<Vec3>& out) const {
  for (size_t i = 0; i < node_.size(); ++i) {
    out[i] = node_[i].mass > mass_floor_ ? (1.0 / node_[i].mass) * node_[i].momentum
                                         : Vec3{0.0, 0.0, 0.0};
  }
  apply_node_constraints(bc, out, true);
}

void MpmSolver::nodal_gradient(const std::vector<Vec3>& v, std::vector<Mat3>& G) const {
  // Dual-domain nodal velocity gradient G_j = sum_i v_i (x) D_ji, later
  // interpolated to the points with N (seed Appendix 2's nodal central
  // difference, in 3-D).
  G.assign(node_.size(), Mat3::Zero());
  for (size_t j = 0; j < G.size(); ++j) {
    for (const auto& e : dual_->row(static_cast<int64_t>(j))) {
      const auto& vi = v[static_cast<size_t>(e.node)];
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b)
          G[j](a, b) += vi[static_cast<size_t>(a)] * e.d[static_cast<size_t>(b)];
      }
    }
  }
}

template <class Stencil>
[[gnu::always_inline]] inline void MpmSolver::velocity_gradient(const MaterialPoints& points,
                                                                size_t p, const Stencil& s,
                                                                const std::vector<Vec3>& v,
                                                                const std::vector<Mat3>& G,
                                                                Mat3& L) const {
  const double al = alpha(points, p);
  double l[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int q = 0; q < s.count; ++q) {
    const auto qq = static_cast<size_t>(q);
    const auto& vi = v[static_cast<size_t>(s.node[qq])];
    const auto& g = s.dN[qq];
    for (size_t a = 0; a < 3; ++a) {
      l[a][0] += vi[a] * g[0];
      l[a][1] += vi[a] * g[1];
      l[a][2] += vi[a] * g[2];
    }
  }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) L(a, b) = al * l[a][b];
  if (opt_.ddmp && al < 1.0) {
    for (int q = 0; q < s.count; ++q) {
      const auto qq = static_cast<size_t>(q);
      L += (1.0 - al) * s.N[qq] * G[static_cast<size_t>(s.node[qq])];
    }
  }
}

// F <- (I + dt L) F and the density from det F; returns det F. Throws if
// the point inverted.
[[gnu::always_inline]] inline double MpmSolver::update_deformation(MaterialPoints& points, size_t p,
                                                                   const Mat3& L, double dt) const {
  points.F[p] = (Mat3::Identity() + dt * L) * points.F[p];
  const double J = points.F[p].determinant();
  if (!(J > 0.0)) [[unlikely]] {
    throw Error(fmt::format(
        "material point {} at ({:.6g}, {:.6g}, {:.6g}) inverted (det F = {:.3g}): the time "
        "step is too large or the material failed",
        points.id[p], points.x[p][0], points.x[p][1], points.x[p][2], J));
  }
  points.state[p].density = points.mass[p] / (points.volume0[p] * J);
  return J;
}

void MpmSolver::update_point_stress(MaterialPoints& points, size_t p, const Mat3& L,
                                    double dt) const {
  const SymmetricTensor D = SymmetricTensor::from_matrix(0.5 * (L + L.transpose()));
  const double power_before = double_contraction(points.state[p].stress, D) * points.volume(p);
  const double J = update_deformation(points, p, L, dt);
  materials_[static_cast<size_t>(points.material[p])]->update(L, dt, points.state[p]);
  // Stress power sigma : D V, by the trapezoidal rule over the step.
  const double power_after = double_contraction(points.state[p].stress, D) * points.volume0[p] * J;
  points.work[p] += 0.5 * dt * (power_before + power_after) * opt_.units.stress_volume_to_energy;
}

void MpmSolver::sum_rigid() {
  if (!patch_.sum_shared) return;
  for (auto& w : rigid_) patch_.sum_shared(w.data(), 1, 1);
}

// Nodes that points of a prescribed-velocity group touch move with the
// group (the rigid-material treatment of NairnMPM and Uintah): material
// next to a piston or grip then cannot flow into it.
void MpmSolver::impose_rigid(const BoundaryConditions& bc, std::vector<Vec3>& v) const {
  for (size_t c = 0; c < bc.point_velocities.size(); ++c) {
    const auto& pv = bc.point_velocities[c];
    for (size_t i = 0; i < v.size(); ++i) {
      if (rigid_[c][i] <= 0.0) continue;
      for (size_t a = 0; a < 3; ++a) {
        if (pv.axis[a]) v[i][a] = pv.velocity[a];
      }
    }
  }
}

// A group with a prescribed velocity moves rigidly at it: the grid's
// velocity there also carries the pressure of the material it pushes, and
// moving the points with it would let a piston drift off its course.
void MpmSolver::hold_prescribed(const MaterialPoints& points, const BoundaryConditions& bc,
                                size_t p, Vec3& vel) const {
  for (const auto& pv : bc.point_velocities) {
    if (!points.in_group(p, pv.group_mask)) continue;
    for (size_t a = 0; a < 3; ++a) {
      if (pv.axis[a]) vel[a] = pv.velocity[a];
    }
  }
}

void MpmSolver::finish_positions(MaterialPoints& points) const {
  const auto& d = patch_.domain;
  for (size_t p = 0; p < points.size(); ++p) {
    Vec3& x = points.x[p];
    x = d.wrapped(x, patch_.periodic);
    if (!d.contains(x)) {
      throw Error(fmt::format("material point {} left the grid at ({:.6g}, {:.6g}, {:.6g})",
                              points.id[p], x[0], x[1], x[2]));
    }
  }
}

void MpmSolver::step(MaterialPoints& points, const BoundaryConditions& bc, double dt) {
  const size_t n = points.size();
  double ref = opt_.reference_point_mass;
  if (ref <= 0.0 && n > 0) ref = *std::min_element(points.mass.begin(), points.mass.end());
  mass_floor_ = ref * opt_.small_mass_fraction;
  if (opt_.ddmp && n > 0)
    dual_ = std::make_unique<grid::DualDomainOperator>(local_, *shape_, points.x);
  // The linear style runs an inlined fixed stencil; any other style goes
  // through its virtual evaluate(), with the same passes.
  if (dynamic_cast<const grid::ShapeFunctionLinear*>(shape_.get()) != nullptr) {
    step_passes(LinearEval{grid::ShapeFunctionLinear::Kernel(local_)}, points, bc, dt);
  } else {
    step_passes(GenericEval{*shape_, local_, {}}, points, bc, dt);
  }
  finish_positions(points);
}

template <class Eval>
void MpmSolver::step_passes(const Eval& eval, MaterialPoints& points, const BoundaryConditions& bc,
                            double dt) {
  const size_t n = points.size();
  const double kf = opt_.units.force_per_mass_to_accel;
  const bool last = opt_.stress_update == StressUpdate::kLast;
  const bool prescribed = !bc.point_velocities.empty();
  Mat3 L;

  if (last) {
    scatter(eval, points, bc, true, true);  // s-1 to s-4
    sum_shared(&node_[0].mass, 7);
    sum_rigid();
  } else {
    // Update-stress-first: the gradient of the mapped velocity updates the
    // stress before it makes the internal force.
    scatter(eval, points, bc, true, false);
    sum_shared(&node_[0].mass, 4);
    sum_rigid();
    nodal_velocities(bc, velocity_);
    impose_rigid(bc, velocity_);
    if (opt_.ddmp) nodal_gradient(velocity_, G_);
    for (size_t p = 0; p < n; ++p) {
      const auto& s = locate(eval, points, p);
      velocity_gradient(points, p, s, velocity_, G_, L);
      update_point_stress(points, p, L, dt);
    }
    scatter(eval, points, bc, true, true);
    sum_shared(&node_[0].mass, 7);
    sum_rigid();
  }

  // Nodal momentum update (s-5, s-6). Constrained components are imposed on
  // the new velocity, and the acceleration is taken from the constrained
  // change, so that FLIP and PIC both honour the constraint.
  for (size_t i = 0; i < node_.size(); ++i) {
    const NodeSums& nd = node_[i];
    node_force_[i] = nd.force;
    if (nd.mass > mass_floor_) {
      const double inv = 1.0 / nd.mass;
      const Vec3 v_old = inv * nd.momentum;
      velocity_[i] = v_old;
      add_scaled(velocity_[i], dt * kf * inv, nd.force);
      acceleration_[i] = v_old;  // completed below
    } else {
      velocity_[i] = acceleration_[i] = {0.0, 0.0, 0.0};
    }
  }
  apply_node_constraints(bc, velocity_, true);
  reaction_.assign(bc.point_velocities.size(), {0.0, 0.0, 0.0});
  for (size_t c = 0; c < bc.point_velocities.size(); ++c) {
    const auto& pv = bc.point_velocities[c];
    for (size_t i = 0; i < node_.size(); ++i) {
      if (rigid_[c][i] <= 0.0) continue;
      for (size_t a = 0; a < 3; ++a) {
        if (!pv.axis[a]) continue;
        // The force that holds the node at the group's velocity, counted
        // once per node over all ranks.
        if (unique_node_[i] && node_[i].mass > mass_floor_) {
          reaction_[c][a] += node_[i].mass * (pv.velocity[a] - velocity_[i][a]) / (dt * kf);
        }
        velocity_[i][a] = pv.velocity[a];
      }
    }
  }
  for (size_t i = 0; i < node_.size(); ++i) {
    if (node_[i].mass > mass_floor_) {
      for (size_t a = 0; a < 3; ++a)
        acceleration_[i][a] = (velocity_[i][a] - acceleration_[i][a]) / dt;
    }
  }

  // Grid to points (s-7), and under update-stress-last the remap of the new
  // point momenta with this step's shape functions (s-10) in the same pass.
  for (auto& nd : node_) nd.momentum = {0.0, 0.0, 0.0};
  const double flip = opt_.flip;
  for (size_t p = 0; p < n; ++p) {
    const auto& s = locate(eval, points, p);
    Vec3 acc{0, 0, 0}, vel{0, 0, 0};
    for (int q = 0; q < s.count; ++q) {
      const auto qq = static_cast<size_t>(q);
      const auto i = static_cast<size_t>(s.node[qq]);
      add_scaled(acc, s.N[qq], acceleration_[i]);
      add_scaled(vel, s.N[qq], velocity_[i]);
    }
    Vec3& vp = points.v[p];
    for (size_t a = 0; a < 3; ++a) {
      vp[a] = flip * (vp[a] + dt * acc[a]) + (1.0 - flip) * vel[a];
    }
    if (prescribed) {
      for (size_t c = 0; c < bc.point_velocities.size(); ++c) {
        const auto& pv = bc.point_velocities[c];
        if (!points.in_group(p, pv.group_mask)) continue;
        for (size_t a = 0; a < 3; ++a) {
          if (!pv.axis[a]) continue;
          vp[a] = pv.velocity[a];
        }
      }
    }
    if (last) {
      const double m = points.mass[p];
      for (int q = 0; q < s.count; ++q) {
        const auto qq = static_cast<size_t>(q);
        add_scaled(node_[static_cast<size_t>(s.node[qq])].momentum, s.N[qq] * m, vp);
      }
    } else {
      if (prescribed) hold_prescribed(points, bc, p, vel);
      add_scaled(points.x[p], dt, vel);  // s-8
    }
  }

  if (!last) return;
  sum_shared(&node_[0].momentum[0], 3);
  nodal_velocities(bc, remap_velocity_);  // s-11
  impose_rigid(bc, remap_velocity_);
  if (opt_.ddmp) nodal_gradient(remap_velocity_, G_);
  // Stress update (s-12 to s-14) at the positions the step started from,
  // then the move with the momentum-update velocity (s-8). Blocks of points:
  // kinematics per point, then one material call per run of points of one
  // material, then the stress power and the move; the result is that of
  // update_point_stress point by point.
  constexpr size_t kBlock = 64;
  std::array<Mat3, kBlock> Lb;
  std::array<SymmetricTensor, kBlock> Db;
  std::array<double, kBlock> power_before, Jb;
  std::array<Vec3, kBlock> vb;
  const double kv = opt_.units.stress_volume_to_energy;
  for (size_t p0 = 0; p0 < n; p0 += kBlock) {
    const size_t m = std::min(kBlock, n - p0);
    for (size_t i = 0; i < m; ++i) {
      const size_t p = p0 + i;
      const auto& s = locate(eval, points, p);
      velocity_gradient(points, p, s, remap_velocity_, G_, Lb[i]);
      Vec3 vel{0, 0, 0};
      for (int q = 0; q < s.count; ++q) {
        const auto qq = static_cast<size_t>(q);
        add_scaled(vel, s.N[qq], velocity_[static_cast<size_t>(s.node[qq])]);
      }
      vb[i] = vel;
      const Mat3& Lp = Lb[i];
      Db[i] = SymmetricTensor::from_matrix(0.5 * (Lp + Lp.transpose()));
      power_before[i] = double_contraction(points.state[p].stress, Db[i]) * points.volume(p);
      Jb[i] = update_deformation(points, p, Lp, dt);
    }
    for (size_t i = 0; i < m;) {
      const int mat = points.material[p0 + i];
      size_t j = i + 1;
      while (j < m && points.material[p0 + j] == mat) ++j;
      materials_[static_cast<size_t>(mat)]->update_many(&Lb[i], dt, &points.state[p0 + i], j - i);
      i = j;
    }
    for (size_t i = 0; i < m; ++i) {
      const size_t p = p0 + i;
      // Stress power sigma : D V, by the trapezoidal rule over the step.
      const double power_after =
          double_contraction(points.state[p].stress, Db[i]) * points.volume0[p] * Jb[i];
      points.work[p] += 0.5 * dt * (power_before[i] + power_after) * kv;
      if (prescribed) hold_prescribed(points, bc, p, vb[i]);
      add_scaled(points.x[p], dt, vb[i]);
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
  return cmax > 0.0 ? patch_.domain.cell_size() / cmax : INFINITY;
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
    e.work += points.work[p];
  }
  return e;
}

}  // namespace pbms::mpm
