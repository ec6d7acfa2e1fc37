#include "pbms/grid/mpm_solver.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/grid/frictionless_contact.hpp"
#include "pbms/grid/shape_function_linear.hpp"
#include "pbms/simd/lane_transpose.hpp"
#include "pbms/units.hpp"

namespace pbms::grid {
namespace {

using Lanes4 = simd::Lanes<4>;  // half a node record: mass and momentum
[[gnu::always_inline]] inline Lanes4 low_half(const Lanes8& l) {
  return __builtin_shufflevector(l, l, 0, 1, 2, 3);
}
[[gnu::always_inline]] inline void set_low_half(NodeLanes& r, const Lanes4& l) {
  __builtin_memcpy(&r, &l, sizeof l);
}

// Requests the entries of points p + kAhead .. p + kAhead + W - 1 of each
// array into the cache. The stress update reads and writes F and the state
// (144 bytes a point) in blocks of 64 points; requested from the gradient
// loop before it, 512 points ahead, they cut the update from 27 to 19 ns a
// point. The same requests in P2G and G2P measured no gain.
inline constexpr size_t kPrefetchAhead = 512;
template <int W, class... Arrays>
[[gnu::always_inline]] inline void prefetch_ahead(size_t n, size_t p, const Arrays&... arrays) {
  if (p + kPrefetchAhead + W > n) return;
  const auto one = [p](const auto& a) {
    const char* b = reinterpret_cast<const char*>(a.data() + p + kPrefetchAhead);
    for (size_t o = 0; o < W * sizeof(a[0]); o += 64) __builtin_prefetch(b + o);
  };
  (one(arrays), ...);
}

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

RegularGrid patch_grid(const GridPatch& patch) {
  const auto& d = patch.domain;
  const auto e = patch.nodes.extent();
  if (patch.nodes.empty() || e[0] < 2 || e[1] < 2 || e[2] < 2 ||
      !(patch.nodes.intersected(d.node_box()) == patch.nodes)) {
    throw Error("MPM solver: the patch must be a box of at least one cell inside the grid");
  }
  std::array<double, 3> origin{};
  for (size_t a = 0; a < 3; ++a) origin[a] = d.origin()[a] + patch.nodes.lo[a] * d.cell_size();
  return RegularGrid(origin, d.cell_size(), {e[0] - 1, e[1] - 1, e[2] - 1});
}

// Shape-function evaluation for the particle passes. The generic one goes
// through the style's virtual evaluate(); the linear one is chosen once per
// step and inlines a fixed 8-node stencil. Both leave the inside check to
// the caller.
// The generic one fills one buffer and returns it; the linear one returns
// its stencil by value, which after inlining lives in registers and drops
// what a pass does not read (the gradients in the G2P pass).
struct GenericEval {
  const ShapeFunction& shape;
  const RegularGrid& grid;
  mutable ShapeStencil buffer;
  const ShapeStencil& operator()(const Vec3& x) const {
    shape.evaluate(grid, x, buffer);
    return buffer;
  }
};

struct LinearEval {
  ShapeFunctionLinear::Kernel kernel;
  LinearStencil operator()(const Vec3& x) const {
    LinearStencil s;
    kernel(x, s);
    return s;
  }
};

}  // namespace

MpmSolver::SimdWidth MpmSolver::simd_width() {
  return {kLanes, simd::kPointLanesIsa};
}

UnitSystem UnitSystem::metal() {
  return {1.0 / units::kBarPerEvPerA3, 1.0 / units::kMvv2e};
}

MpmSolver::MpmSolver(GridPatch patch, std::unique_ptr<ShapeFunction> shape,
                     std::vector<std::unique_ptr<Material>> materials, SolverOptions options)
    : patch_(std::move(patch)),
      local_(patch_grid(patch_)),
      shape_(std::move(shape)),
      materials_(std::move(materials)),
      opt_(std::move(options)),
      linear_(dynamic_cast<const ShapeFunctionLinear*>(shape_.get()) != nullptr),
      block_(std::make_unique<MaterialBlock>()) {
  const auto n = static_cast<size_t>(local_.node_count());
  sums_.assign(n, NodeLanes{});
  kin_.assign(n, NodeLanes{});
  velocity_.assign(n, {0.0, 0.0, 0.0});
  acceleration_.assign(n, {0.0, 0.0, 0.0});
  remap_velocity_.assign(n, {0.0, 0.0, 0.0});
  node_force_.assign(n, {0.0, 0.0, 0.0});
  if (opt_.contact != ContactField::kNone) {
    if (opt_.stress_update != StressUpdate::kLast) {
      throw Error("a contact field takes update-stress-last");
    }
    mass_gradient_.assign(3 * n, 0.0);
    other_gradient_.assign(3 * n, 0.0);
    other_sums_.assign(sums::kStride * n, 0.0);
  }
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

void MpmSolver::evaluate(const MaterialPoints& points, size_t p, ShapeStencil& s) const {
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
    ShapeStencil unused;
    evaluate(points, p, unused);  // throws, naming the point
  }
  return eval(points.x[p]);
}

double MpmSolver::alpha(const MaterialPoints& points, size_t p) const {
  if (!opt_.ddmp) return 1.0;
  return opt_.ddmp_face_vanishing ? face_vanishing_blend(local_, points.x[p]) : 0.0;
}

void MpmSolver::sum_shared(int first, int components) {
  if (patch_.sum_shared) {
    patch_.sum_shared(reinterpret_cast<double*>(sums_.data()) + first, components, sums::kStride);
  }
}

// Body force, the loads of the point's groups and its own point force, eV/Å.
Vec3 MpmSolver::external_force(const MaterialPoints& points, const BoundaryConditions& bc,
                               size_t p) const {
  Vec3 f{0.0, 0.0, 0.0};
  if (dot(bc.body_acceleration, bc.body_acceleration) > 0.0) {
    f = (points.mass[p] / opt_.units.force_per_mass_to_accel) * bc.body_acceleration;
  }
  for (const auto& load : bc.loads) {
    if (points.in_group(p, load.group_mask)) add_to(f, load.force_per_point);
  }
  if (!bc.point_forces.empty()) add_to(f, bc.point_forces[p]);
  return f;
}

// Mass, momentum and optionally the internal and external forces of every
// point to its nodes (s-1 to s-4). The forces use the stress the points
// carry now, which under update-stress-last is the previous step's. A
// point adds to each node N (m, m v, f_ext) - V sigma grad N as one
// record: four whole-record multiply-adds per node.
template <class Eval>
void MpmSolver::scatter(const Eval& eval, const MaterialPoints& points,
                        const BoundaryConditions& bc, bool force) {
  std::fill(sums_.begin(), sums_.end(), NodeLanes{});
  rigid_.assign(bc.point_velocities.size(), std::vector<double>(sums_.size(), 0.0));
  const bool dual = force && opt_.ddmp;
  if (dual) S_.assign(sums_.size(), {0, 0, 0, 0, 0, 0});
  const double kv = opt_.units.stress_volume_to_energy;
  const bool body = dot(bc.body_acceleration, bc.body_acceleration) > 0.0;
  const bool external = body || !bc.loads.empty() || !bc.point_forces.empty();
  const bool rigid = !bc.point_velocities.empty();
  size_t first = 0;
  if constexpr (std::is_same_v<Eval, LinearEval>) {
    if (force && !dual) {
      for (; first + kLanes <= points.size(); first += kLanes)
        scatter_lanes(eval.kernel, points, bc, external, first);
    }
  }
  for (size_t p = first; p < points.size(); ++p) {
    decltype(auto) s = locate(eval, points, p);
    keep_weights_in_memory(s);
    const double m = points.mass[p];
    const Vec3& v = points.v[p];
    Lanes8 pn = {m, m * v[0], m * v[1], m * v[2], 0.0, 0.0, 0.0, 0.0};
    Lanes8 gx{}, gy{}, gz{};
    double V = 0.0, al = 1.0;
    if (force) {
      if (external) [[unlikely]] {
        const Vec3 fext = external_force(points, bc, p);
        pn[sums::kForce] = fext[0];
        pn[sums::kForce + 1] = fext[1];
        pn[sums::kForce + 2] = fext[2];
      }
      V = points.volume(p) * kv;
      if (dual) al = alpha(points, p);
      const double w = -al * V;
      const auto& t = points.state[p].stress.voigt;  // xx yy zz yz xz xy
      gx = Lanes8{0.0, 0.0, 0.0, 0.0, w * t[0], w * t[5], w * t[4], 0.0};
      gy = Lanes8{0.0, 0.0, 0.0, 0.0, w * t[5], w * t[1], w * t[3], 0.0};
      gz = Lanes8{0.0, 0.0, 0.0, 0.0, w * t[4], w * t[3], w * t[2], 0.0};
    }
    if (rigid) [[unlikely]] {
      for (size_t c = 0; c < bc.point_velocities.size(); ++c) {
        if (!points.in_group(p, bc.point_velocities[c].group_mask)) continue;
        for (int q = 0; q < s.count; ++q) {
          const auto qq = static_cast<size_t>(q);
          if (s.N[qq] > 0.0) rigid_[c][static_cast<size_t>(s.node[qq])] += s.N[qq] * m;
        }
      }
    }
    for (int q = 0; q < s.count; ++q) {
      const auto qq = static_cast<size_t>(q);
      const auto g = grad(s, q);
      sums_[static_cast<size_t>(s.node[qq])].lanes +=
          s.N[qq] * pn + g[0] * gx + g[1] * gy + g[2] * gz;
    }
    if (dual && al < 1.0) {
      const auto& t = points.state[p].stress.voigt;
      for (int q = 0; q < s.count; ++q) {
        const auto qq = static_cast<size_t>(q);
        auto& S = S_[static_cast<size_t>(s.node[qq])];
        const double wd = (1.0 - al) * V * s.N[qq];
        for (size_t c = 0; c < 6; ++c) S[c] += wd * t[c];
      }
    }
  }
}

// The scalar loop's records and sums, in its order, for kLanes points: the
// stencil, volume and stress products run across lanes and are transposed
// into per-point records; each point's corner weights are read back as
// broadcasts.
void MpmSolver::scatter_lanes(const ShapeFunctionLinear::Kernel& kernel,
                              const MaterialPoints& points, const BoundaryConditions& bc,
                              bool external, size_t p) {
  constexpr int W = kLanes;
  const LinearStencilLanes<W> s = locate_lanes(kernel, points, p);
  // [0][q]: corner q's N, [1..3][q]: its gradient, across the points.
  PointLanes wt[4][8];
  for (int q = 0; q < 8; ++q) {
    PointLanes g[3];
    s.dN(q, g);
    wt[0][q] = s.N(q);
    for (int a = 0; a < 3; ++a) wt[1 + a][q] = g[a];
  }
  asm("" : "+m"(wt));  // broadcast loads, as keep_weights_in_memory
  PointLanes m, v0, v[3], F[9], t[9];
  __builtin_memcpy(&m, &points.mass[p], sizeof m);
  __builtin_memcpy(&v0, &points.volume0[p], sizeof v0);
  simd::deinterleave3<W>(&points.v[p], v);
  simd::load_records<W, 9>(points.F[p].data(), F);
  simd::load_records<W, 9>(points.state[p].stress.voigt.data(), t);
  // Eigen's 3 x 3 determinant (F column by column: F(r, c) is F[3 c + r]).
  const PointLanes det = F[0] * (F[4] * F[8] - F[7] * F[5]) - F[3] * (F[1] * F[8] - F[7] * F[2]) +
                         F[6] * (F[1] * F[5] - F[4] * F[2]);
  const PointLanes V = v0 * det * opt_.units.stress_volume_to_energy;
  const PointLanes w = -(1.0 * V);
  const PointLanes z{};
  PointLanes fext[3] = {z, z, z};
  if (external) [[unlikely]] {
    for (size_t k = 0; k < W; ++k) {
      const Vec3 f = external_force(points, bc, p + k);
      for (size_t a = 0; a < 3; ++a) fext[a][k] = f[a];
    }
  }
  // Built whole rather than patched lane by lane afterwards: patching kept
  // the array in memory, zeroed by a rep stos per eight points.
  static_assert(sums::kForce == 4);
  const PointLanes pn[8] = {m, m * v[0], m * v[1], m * v[2], fext[0], fext[1], fext[2], z};
  const PointLanes gx[8] = {z, z, z, z, w * t[0], w * t[5], w * t[4], z};
  const PointLanes gy[8] = {z, z, z, z, w * t[5], w * t[1], w * t[3], z};
  const PointLanes gz[8] = {z, z, z, z, w * t[4], w * t[3], w * t[2], z};
  Lanes8 pr[W], gxr[W], gyr[W], gzr[W];  // per point, records of eight fields
  simd::lanes_to_records8<W>(pn, pr);
  simd::lanes_to_records8<W>(gx, gxr);
  simd::lanes_to_records8<W>(gy, gyr);
  simd::lanes_to_records8<W>(gz, gzr);
  for (size_t k = 0; k < W; ++k) {
    NodeLanes* cell = sums_.data() + s.base[k];
    for (int q = 0; q < 8; ++q) {
      s.corner(cell, q)->lanes +=
          wt[0][q][k] * pr[k] + wt[1][q][k] * gxr[k] + wt[2][q][k] * gyr[k] + wt[3][q][k] * gzr[k];
    }
  }
  for (size_t c = 0; c < bc.point_velocities.size(); ++c) {
    for (size_t k = 0; k < W; ++k) {
      if (!points.in_group(p + k, bc.point_velocities[c].group_mask)) continue;
      for (int q = 0; q < 8; ++q) {
        const double N = wt[0][q][k];
        if (N > 0.0) rigid_[c][static_cast<size_t>(s.node(k, q))] += N * points.mass[p + k];
      }
    }
  }
}

// Dual-domain part of the internal force, f_i -= sum_j (S_j / V_j) . M_ji,
// after the node sums: S_j and V_j are completed across ranks first, then
// each rank spreads the nodal average stress over its own cells' rows, and
// those parts are summed in turn (see DualDomainRows).
void MpmSolver::add_dual_force() {
  if (patch_.sum_shared) patch_.sum_shared(S_.data()->data(), 6, 6);
  dual_force_.assign(sums_.size(), {0.0, 0.0, 0.0});
  for (size_t j = 0; j < S_.size(); ++j) {
    if (!(dual_volume_[j] > 0.0)) continue;
    auto t = S_[j];
    if (t == std::array<double, 6>{0, 0, 0, 0, 0, 0}) continue;
    for (auto& c : t) c /= dual_volume_[j];
    for (const auto& e : dual_->row(static_cast<int64_t>(j))) {
      auto& f = dual_force_[static_cast<size_t>(e.node)];
      const auto& d = e.d;
      f[0] -= t[0] * d[0] + t[5] * d[1] + t[4] * d[2];
      f[1] -= t[5] * d[0] + t[1] * d[1] + t[3] * d[2];
      f[2] -= t[4] * d[0] + t[3] * d[1] + t[2] * d[2];
    }
  }
  if (patch_.sum_shared) patch_.sum_shared(dual_force_.data()->data(), 3, 3);
  for (size_t i = 0; i < sums_.size(); ++i) {
    auto& f = sums_[i].lanes;
    for (int a = 0; a < 3; ++a) f[sums::kForce + a] += dual_force_[i][static_cast<size_t>(a)];
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

// The momentum the constraints are about to give the nodes (each node
// counted on one rank only): sum of m (v_held - v) over the held axes, which
// both PIC and FLIP hand on to the points whole. `face_push`: the part
// along the inward normal of entries that hold one of the grid's outer
// node planes.
Vec3 MpmSolver::node_constraint_impulse(const BoundaryConditions& bc, double& face_push) const {
  Vec3 impulse{0.0, 0.0, 0.0};
  face_push = 0.0;
  const NodeBox all = patch_.domain.node_box();
  for (const auto& c : bc.nodes) {
    Vec3 inward{0.0, 0.0, 0.0};
    for (size_t a = 0; a < 3; ++a) {
      if (!c.axis[a] || c.nodes.hi[a] - c.nodes.lo[a] != 1) continue;
      if (c.nodes.lo[a] == all.lo[a]) inward[a] = 1.0;
      if (c.nodes.lo[a] == all.hi[a] - 1) inward[a] = -1.0;
    }
    const auto box = c.nodes.intersected(patch_.nodes);
    for (int k = box.lo[2]; k < box.hi[2]; ++k) {
      for (int j = box.lo[1]; j < box.hi[1]; ++j) {
        for (int i = box.lo[0]; i < box.hi[0]; ++i) {
          const auto li = static_cast<size_t>(patch_.nodes.local_index({i, j, k}));
          const double mass = sums_[li].lanes[sums::kMass];
          if (!unique_node_[li] || !(mass > mass_floor_)) continue;
          for (size_t a = 0; a < 3; ++a) {
            if (!c.axis[a]) continue;
            const double j = mass * (c.velocity[a] - velocity_[li][a]);
            impulse[a] += j;
            face_push += inward[a] * j;
          }
        }
      }
    }
  }
  return impulse;
}

void MpmSolver::nodal_velocities(const BoundaryConditions& bc, std::vector<Vec3>& out) const {
  for (size_t i = 0; i < sums_.size(); ++i) {
    const Lanes8& r = sums_[i].lanes;
    out[i] = r[sums::kMass] > mass_floor_ ? (1.0 / r[sums::kMass]) * lanes3(r, sums::kMomentum)
                                          : Vec3{0.0, 0.0, 0.0};
  }
  apply_node_constraints(bc, out, true);
}

void MpmSolver::nodal_gradient(const std::vector<Vec3>& v, std::vector<Mat3>& G) const {
  // Dual-domain nodal velocity gradient G_j = sum_i v_i (x) D_ji, later
  // interpolated to the points with N (seed Appendix 2's nodal central
  // difference, in 3-D): each rank's rows M_ji give its part, and the parts
  // are summed before the division by V_j.
  G.assign(sums_.size(), Mat3::Zero());
  for (size_t j = 0; j < G.size(); ++j) {
    for (const auto& e : dual_->row(static_cast<int64_t>(j))) {
      const auto& vi = v[static_cast<size_t>(e.node)];
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b)
          G[j](a, b) += vi[static_cast<size_t>(a)] * e.d[static_cast<size_t>(b)];
      }
    }
  }
  static_assert(sizeof(Mat3) == 9 * sizeof(double));
  if (patch_.sum_shared) patch_.sum_shared(G.data()->data(), 9, 9);
  for (size_t j = 0; j < G.size(); ++j) {
    if (dual_volume_[j] > 0.0) G[j] /= dual_volume_[j];
  }
}

void MpmSolver::pack_kinematics(const std::vector<Vec3>& first, const std::vector<Vec3>& second) {
  for (size_t i = 0; i < kin_.size(); ++i) {
    const Vec3& a = first[i];
    const Vec3& b = second[i];
    kin_[i].lanes = Lanes8{a[0], a[1], a[2], b[0], b[1], b[2], 0.0, 0.0};
  }
}

template <class Stencil>
[[gnu::always_inline]] inline void MpmSolver::point_kinematics(const MaterialPoints& points,
                                                               size_t p, const Stencil& s, Mat3& L,
                                                               Vec3& carried) const {
  // Lanes 0-2 of lx, ly, lz are the columns of grad v; lanes 3-5 of at are
  // the carried field.
  Lanes8 at{}, lx{}, ly{}, lz{};
  for (int q = 0; q < s.count; ++q) {
    const auto qq = static_cast<size_t>(q);
    const Lanes8& r = kin_[static_cast<size_t>(s.node[qq])].lanes;
    const auto g = grad(s, q);
    at += s.N[qq] * r;
    lx += g[0] * r;
    ly += g[1] * r;
    lz += g[2] * r;
  }
  carried = lanes3(at, 3);
  const double al = alpha(points, p);
  for (int a = 0; a < 3; ++a) {
    L(a, 0) = al * lx[a];
    L(a, 1) = al * ly[a];
    L(a, 2) = al * lz[a];
  }
  if (opt_.ddmp && al < 1.0) {
    for (int q = 0; q < s.count; ++q) {
      const auto qq = static_cast<size_t>(q);
      L += (1.0 - al) * s.N[qq] * G_[static_cast<size_t>(s.node[qq])];
    }
  }
}

[[gnu::always_inline]] inline LinearStencilLanes<MpmSolver::kLanes> MpmSolver::locate_lanes(
    const ShapeFunctionLinear::Kernel& kernel, const MaterialPoints& points, size_t p) const {
  PointLanes x[3];
  simd::deinterleave3<kLanes>(&points.x[p], x);
  check_inside_lanes(points, p, x);
  LinearStencilLanes<kLanes> s;
  kernel(x, s);
  return s;
}

void MpmSolver::check_inside_lanes(const MaterialPoints& points, size_t p,
                                   const PointLanes (&x)[3]) const {
  const auto& lo = local_.origin();
  const auto& hi = local_.upper();
  using Mask = simd::IndexLanes<kLanes>;
  Mask in = (x[0] >= lo[0]) & (x[0] <= hi[0]);
  in &= (x[1] >= lo[1]) & (x[1] <= hi[1]);
  in &= (x[2] >= lo[2]) & (x[2] <= hi[2]);
  if (!simd::all_lanes_set<kLanes>(in)) [[unlikely]] {
    ShapeStencil unused;
    for (size_t k = 0; k < kLanes; ++k) evaluate(points, p + k, unused);  // throws at the first
  }
}

// The same sums as point_kinematics with the linear stencil, in the same
// order, point k of the kLanes in lane k: node q's records for the points
// are transposed into one vector per field, so that each term of L is one
// multiply-add for all of them.
void MpmSolver::point_kinematics_lanes(const ShapeFunctionLinear::Kernel& kernel,
                                       const MaterialPoints& points, size_t p, MaterialBlock& b,
                                       size_t i, Vec3* carried) const {
  constexpr int W = kLanes;
  // For the stress update of this block, which reads and writes both.
  prefetch_ahead<W>(points.size(), p, points.F, points.state);
  const LinearStencilLanes<W> s = locate_lanes(kernel, points, p);
  PointLanes L[9]{}, at[3]{};
  const NodeLanes* kin = kin_.data();
  for (int q = 0; q < 8; ++q) {
    const Lanes8* rec[W];
    for (size_t k = 0; k < W; ++k) rec[k] = &s.corner(kin + s.base[k], q)->lanes;
    PointLanes r[8];
    simd::records8_to_lanes<W>(rec, r);
    const PointLanes N = s.N(q);
    PointLanes g[3];
    s.dN(q, g);
    for (int a = 0; a < 3; ++a) {
      for (int c = 0; c < 3; ++c) L[3 * a + c] += g[c] * r[a];
      at[a] += N * r[3 + a];
    }
  }
  for (int k = 0; k < 9; ++k) __builtin_memcpy(&b.L[k][i], &L[k], sizeof(PointLanes));
  simd::interleave3<W>(at, carried);
}

// The scalar G2P loop's arithmetic, in its order, for kLanes points: their
// corner weights come from one evaluation across lanes, read back per
// point as broadcasts; the velocity update runs across lanes.
void MpmSolver::grid_to_points_lanes(const ShapeFunctionLinear::Kernel& kernel,
                                     MaterialPoints& points, const BoundaryConditions& bc, size_t p,
                                     double dt) {
  constexpr int W = kLanes;
  const LinearStencilLanes<W> s = locate_lanes(kernel, points, p);
  PointLanes w[8];  // w[q][k]: point k's weight at corner q
  for (int q = 0; q < 8; ++q) w[q] = s.N(q);
  asm("" : "+m"(w));  // broadcast loads, as keep_weights_in_memory
  const NodeLanes* kin = kin_.data();
  Lanes8 at[W];  // per point: lanes 0-2 acceleration, 3-5 velocity
  for (size_t k = 0; k < W; ++k) {
    const NodeLanes* cell = kin + s.base[k];
    Lanes8 a{};
    for (int q = 0; q < 8; ++q) a += w[q][k] * s.corner(cell, q)->lanes;
    at[k] = a;
  }
  PointLanes f[8];  // the same, one vector per lane of the records
  {
    const Lanes8* rec[W];
    for (size_t k = 0; k < W; ++k) rec[k] = &at[k];
    simd::records8_to_lanes<W>(rec, f);
  }
  PointLanes v[3];
  simd::deinterleave3<W>(&points.v[p], v);
  const double flip = opt_.flip;
  for (int a = 0; a < 3; ++a) v[a] = flip * (v[a] + dt * f[a]) + (1.0 - flip) * f[a + 3];
  simd::interleave3<W>(v, &points.v[p]);
  if (!bc.point_velocities.empty()) [[unlikely]] {
    for (size_t k = 0; k < W; ++k) hold_prescribed(points, bc, p + k, points.v[p + k]);
    simd::deinterleave3<W>(&points.v[p], v);  // the remap takes the held velocities
  }
  if (opt_.stress_update == StressUpdate::kFirst) {
    // No remap: the points move with the grid velocity (s-8).
    Vec3 vel[W];
    simd::interleave3<W>({f[3], f[4], f[5]}, vel);
    for (size_t k = 0; k < W; ++k) {
      hold_prescribed(points, bc, p + k, vel[k]);
      move_point(points, p + k, vel[k], dt);
    }
    return;
  }
  PointLanes m;
  __builtin_memcpy(&m, &points.mass[p], sizeof m);
  const PointLanes z{};
  const PointLanes pm[8] = {z, m * v[0], m * v[1], m * v[2], z, z, z, z};
  Lanes8 pmr[W];
  simd::lanes_to_records8<W>(pm, pmr);
  // Only the mass-and-momentum half of each record changes: half the stores.
  for (size_t k = 0; k < W; ++k) {
    const Lanes4 pm4 = low_half(pmr[k]);
    NodeLanes* cell = sums_.data() + s.base[k];
    for (int q = 0; q < 8; ++q) {
      NodeLanes* r = s.corner(cell, q);
      set_low_half(*r, low_half(r->lanes) + w[q][k] * pm4);
    }
  }
}

namespace {

// det of a 3x3 matrix held row by row in nine scalars (Eigen's cofactor
// expansion, written out so that a loop over points vectorises).
[[gnu::always_inline]] inline double det3(const double (&f)[9]) {
  return f[0] * (f[4] * f[8] - f[7] * f[5]) - f[3] * (f[1] * f[8] - f[7] * f[2]) +
         f[6] * (f[1] * f[5] - f[4] * f[2]);
}

// sigma : sym(L) for point i of a block.
[[gnu::always_inline]] inline double stress_power_density(const MaterialBlock& b, size_t i) {
  const double d3 = 0.5 * (b.L[5][i] + b.L[7][i]);
  const double d4 = 0.5 * (b.L[2][i] + b.L[6][i]);
  const double d5 = 0.5 * (b.L[1][i] + b.L[3][i]);
  return b.stress[0][i] * b.L[0][i] + b.stress[1][i] * b.L[4][i] + b.stress[2][i] * b.L[8][i] +
         2.0 * (b.stress[3][i] * d3 + b.stress[4][i] * d4 + b.stress[5][i] * d5);
}

}  // namespace

// Stress update (s-12 to s-14) of points p0 .. p0 + m - 1, whose velocity
// gradients b.L holds: F <- (I + dt L) F, the density from det F, the
// material's stress update, and the stress power sigma : D V integrated by
// the trapezoidal rule into the point's work. The points are transposed
// into columns first, so that each loop below runs across points in SIMD
// registers. Throws, naming the point, if one inverted.
void MpmSolver::update_stress_block(MaterialPoints& points, size_t p0, size_t m, MaterialBlock& b,
                                    double dt) const {
  constexpr size_t K = MaterialBlock::kSize;
  alignas(64) double F[9][K];
  alignas(64) double J[K], v0[K], power_before[K], work_increment[K];
  static_assert(sizeof(Mat3) == 9 * sizeof(double));
  static_assert(sizeof(MaterialPointState) == 9 * sizeof(double));
  // kLanes points at a time by transposes (F is stored column by column),
  // the rest point by point.
  constexpr int W = kLanes;
  constexpr size_t kBytes = sizeof(PointLanes);
  const size_t mw = m - m % W;
  for (size_t i = 0; i < mw; i += W) {
    const size_t p = p0 + i;
    PointLanes c[9];
    simd::load_records<W, 9>(points.F[p].data(), c);
    for (int r = 0; r < 3; ++r) {
      for (int col = 0; col < 3; ++col)
        __builtin_memcpy(&F[3 * r + col][i], &c[3 * col + r], kBytes);
    }
    simd::load_records<W, 9>(points.state[p].stress.voigt.data(), c);
    for (int f = 0; f < 6; ++f) __builtin_memcpy(&b.stress[f][i], &c[f], kBytes);
    __builtin_memcpy(&b.plastic_strain[i], &c[7], kBytes);
    __builtin_memcpy(&b.internal_energy[i], &c[8], kBytes);
    __builtin_memcpy(&b.density[i], &points.mass[p], kBytes);
    __builtin_memcpy(&v0[i], &points.volume0[p], kBytes);
  }
  for (size_t i = mw; i < m; ++i) {
    const size_t p = p0 + i;
    const Mat3& f = points.F[p];
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) F[3 * r + c][i] = f(r, c);
    }
    b.set_state(i, points.state[p]);
    b.density[i] = points.mass[p];  // divided by the new volume below
    v0[i] = points.volume0[p];
  }
  for (size_t i = 0; i < m; ++i) {
    double f[9], g[9];
    for (int k = 0; k < 9; ++k) f[k] = F[k][i];
    power_before[i] = stress_power_density(b, i) * v0[i] * det3(f);
    for (size_t r = 0; r < 3; ++r) {
      const double l0 = b.L[3 * r][i], l1 = b.L[3 * r + 1][i], l2 = b.L[3 * r + 2][i];
      for (size_t c = 0; c < 3; ++c)
        g[3 * r + c] = f[3 * r + c] + dt * (l0 * f[c] + l1 * f[3 + c] + l2 * f[6 + c]);
    }
    for (int k = 0; k < 9; ++k) F[k][i] = g[k];
    J[i] = det3(g);
    b.density[i] /= v0[i] * J[i];
  }
  for (size_t i = 0; i < m; ++i) {
    if (!(J[i] > 0.0)) [[unlikely]] {
      const size_t p = p0 + i;
      if (!materials_[static_cast<size_t>(points.material[p])]->tracks_deformation()) continue;
      const char* what = std::isnan(J[i])
                             ? "has a non-finite deformation gradient (det F = {:.3g}): the step "
                               "blew up"
                             : "inverted (det F = {:.3g}): the time step is too large or the "
                               "material failed";
      throw Error(fmt::format(
          "{} {} at ({:.6g}, {:.6g}, {:.6g}) {}", opt_.noun_of(points.material[p]), points.id[p],
          points.x[p][0], points.x[p][1], points.x[p][2], fmt::format(fmt::runtime(what), J[i])));
    }
  }
  for (size_t i = 0; i < m;) {
    const int mat = points.material[p0 + i];
    size_t j = i + 1;
    while (j < m && points.material[p0 + j] == mat) ++j;
    materials_[static_cast<size_t>(mat)]->update_block(b, i, j, dt);
    i = j;
  }
  const double kv = opt_.units.stress_volume_to_energy;
  for (size_t i = 0; i < m; ++i) {
    const double power_after = stress_power_density(b, i) * v0[i] * J[i];
    work_increment[i] = 0.5 * dt * (power_before[i] + power_after) * kv;
  }
  for (size_t i = 0; i < mw; i += W) {
    const size_t p = p0 + i;
    PointLanes c[9];
    for (int r = 0; r < 3; ++r) {
      for (int col = 0; col < 3; ++col)
        __builtin_memcpy(&c[3 * col + r], &F[3 * r + col][i], kBytes);
    }
    simd::store_records<W, 9>(c, points.F[p].data());
    for (int f = 0; f < 6; ++f) __builtin_memcpy(&c[f], &b.stress[f][i], kBytes);
    __builtin_memcpy(&c[6], &b.density[i], kBytes);
    __builtin_memcpy(&c[7], &b.plastic_strain[i], kBytes);
    __builtin_memcpy(&c[8], &b.internal_energy[i], kBytes);
    simd::store_records<W, 9>(c, points.state[p].stress.voigt.data());
    PointLanes w, dw;
    __builtin_memcpy(&w, &points.work[p], kBytes);
    __builtin_memcpy(&dw, &work_increment[i], kBytes);
    w += dw;
    __builtin_memcpy(&points.work[p], &w, kBytes);
  }
  for (size_t i = mw; i < m; ++i) {
    const size_t p = p0 + i;
    Mat3& f = points.F[p];
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) f(r, c) = F[3 * r + c][i];
    }
    points.state[p] = b.state(i);
    points.work[p] += work_increment[i];
  }
}

// Moves point p by dt v and wraps it on periodic axes; throws, naming the
// point, if it left the grid. The test against the grid's half-open box
// settles nearly every point without the wrap.
[[gnu::always_inline]] inline void MpmSolver::move_point(MaterialPoints& points, size_t p,
                                                         const Vec3& v, double dt) const {
  Vec3& x = points.x[p];
  add_scaled(x, dt, v);
  const auto& d = patch_.domain;
  const auto& lo = d.origin();
  const auto& hi = d.upper();
  if (x[0] >= lo[0] && x[0] < hi[0] && x[1] >= lo[1] && x[1] < hi[1] && x[2] >= lo[2] &&
      x[2] < hi[2]) [[likely]] {
    return;
  }
  x = d.wrapped(x, patch_.periodic);
  if (!d.contains(x)) point_off_grid(opt_.noun_of(points.material[p]), points.id[p], x, v, dt);
}

// A point whose position is not finite did not leave the grid: the step
// blew up (a NaN force or velocity), and the message says so.
// One that jumped more than half a cell in its last step names the likely
// cause, a time step too large for the model.
void MpmSolver::point_off_grid(const std::string& noun, int64_t id, const Vec3& x, const Vec3& v,
                               double dt) const {
  if (std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2])) {
    const double jump = dt * std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double h = patch_.domain.cell_size();
    const std::string cause =
        jump > 0.5 * h ? fmt::format(
                             ": its last step moved it {:.3g} Å, {:.2g} cells, at {:.4g} "
                             "Å/ps; a time step of {:g} ps is too large for this motion "
                             "(or the model blew up)",
                             jump, jump / h, jump / dt, dt)
                       : "";
    throw Error(fmt::format("{} {} left the grid at ({:.6g}, {:.6g}, {:.6g}){}", noun, id, x[0],
                            x[1], x[2], cause));
  }
  throw Error(
      fmt::format("{} {} has a non-finite position ({:.6g}, {:.6g}, {:.6g}), velocity "
                  "({:.6g}, {:.6g}, {:.6g}) Å/ps: the step blew up",
                  noun, id, x[0], x[1], x[2], v[0], v[1], v[2]));
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

void MpmSolver::build_dual(const MaterialPoints& points) {
  // Built from this rank's points over its own cells, as integrals, so that
  // the parts of V_j and of the rows at shared nodes add up across ranks.
  dual_ = std::make_unique<DualDomainOperator>(local_, *shape_, points.x, DualDomainQuadrature{},
                                               DualDomainRows::kIntegral);
  dual_volume_.resize(sums_.size());
  for (size_t j = 0; j < dual_volume_.size(); ++j)
    dual_volume_[j] = dual_->nodal_volume(static_cast<int64_t>(j));
  if (patch_.sum_shared) patch_.sum_shared(dual_volume_.data(), 1, 1);
}

template <class F>
void MpmSolver::with_eval(F&& pass) {
  // The linear style runs an inlined fixed stencil; any other style goes
  // through its virtual evaluate(), with the same passes.
  if (linear_) {
    pass(LinearEval{ShapeFunctionLinear::Kernel(local_)});
  } else {
    pass(GenericEval{*shape_, local_, {}});
  }
}

void MpmSolver::enter(Phase next) {
  if (phase_ != next) {
    throw Error(fmt::format("MPM solver: step phase {} called when phase {} was due",
                            static_cast<int>(next), static_cast<int>(phase_)));
  }
  constexpr int kPhases = static_cast<int>(Phase::kUpdateStress) + 1;
  phase_ = static_cast<Phase>((static_cast<int>(next) + 1) % kPhases);
}

void MpmSolver::step(MaterialPoints& points, const BoundaryConditions& bc, double dt) {
  begin_step(points);
  map_to_grid(points, bc, dt);
  complete_nodal_sums();
  update_nodes(bc, dt);
  map_to_points(points, bc, dt);
  complete_remap_sums();
  update_stress_and_move(points, bc, dt);
}

void MpmSolver::begin_step(const MaterialPoints& points) {
  enter(Phase::kBegin);
  others_held_.clear();
  double ref = opt_.reference_point_mass;
  if (ref <= 0.0 && points.size() > 0)
    ref = *std::min_element(points.mass.begin(), points.mass.end());
  mass_floor_ = ref * opt_.small_mass_fraction;
  if (opt_.ddmp) build_dual(points);
}

void MpmSolver::map_to_grid(MaterialPoints& points, const BoundaryConditions& bc, double dt) {
  enter(Phase::kMapToGrid);
  if (opt_.stress_update == StressUpdate::kLast) {
    with_eval([&](const auto& eval) {
      scatter(eval, points, bc, true);  // s-1 to s-4
      if (opt_.contact == ContactField::kSurfaceFromOwnMass) map_mass_gradient(eval, points);
    });
    return;
  }
  // Update-stress-first: the gradient of the mapped velocity updates the
  // stress before it makes the internal force. That gradient needs the
  // complete nodal velocities, so this phase sums over the solver's ranks
  // once itself (a coupled run must use update-stress-last).
  with_eval([&](const auto& eval) { scatter(eval, points, bc, false); });
  sum_shared(sums::kMass, 4);
  sum_rigid();
  nodal_velocities(bc, velocity_);
  impose_rigid(bc, velocity_);
  if (opt_.ddmp) nodal_gradient(velocity_, G_);
  pack_kinematics(velocity_, velocity_);
  with_eval([&](const auto& eval) {
    const size_t n = points.size();
    Mat3 L;
    Vec3 unused;
    for (size_t p0 = 0; p0 < n; p0 += MaterialBlock::kSize) {
      const size_t m = std::min(MaterialBlock::kSize, n - p0);
      for (size_t i = 0; i < m; ++i) {
        decltype(auto) s = locate(eval, points, p0 + i);
        keep_weights_in_memory(s);
        point_kinematics(points, p0 + i, s, L, unused);
        block_->set_velocity_gradient(i, L);
      }
      update_stress_block(points, p0, m, *block_, dt);
    }
    scatter(eval, points, bc, true);
  });
}

void MpmSolver::complete_nodal_sums() {
  enter(Phase::kCompleteNodalSums);
  sum_shared(sums::kMass, 7);
  if (opt_.contact == ContactField::kSurfaceFromOwnMass && patch_.sum_shared) {
    patch_.sum_shared(mass_gradient_.data(), 3, 3);
  }
  if (opt_.ddmp) add_dual_force();
  sum_rigid();
}

MpmSolver::NodalSums MpmSolver::nodal_sums() {
  return {reinterpret_cast<double*>(sums_.data()), sums::kStride, patch_.nodes};
}

MpmSolver::ContactFields MpmSolver::contact_fields() {
  if (opt_.contact == ContactField::kNone)
    throw Error("this grid step keeps no contact fields (SolverOptions::contact)");
  return {{mass_gradient_.data(), 3, patch_.nodes},
          {other_sums_.data(), sums::kStride, patch_.nodes},
          {other_gradient_.data(), 3, patch_.nodes}};
}

// Σ_p m_p ∇N_i(x_p) points from the points to node i; its negative is the
// gradient at the node of the mass the points spread, which points into
// their material (the normal frictionless_contact.hpp takes).
template <class Eval>
void MpmSolver::map_mass_gradient(const Eval& eval, const MaterialPoints& points) {
  std::fill(mass_gradient_.begin(), mass_gradient_.end(), 0.0);
  for (size_t p = 0; p < points.size(); ++p) {
    const auto& s = locate(eval, points, p);
    for (int q = 0; q < s.count; ++q) {
      double* g = &mass_gradient_[3 * static_cast<size_t>(s.node[static_cast<size_t>(q)])];
      const auto dN = grad(s, q);
      for (size_t a = 0; a < 3; ++a) g[a] -= points.mass[p] * dN[a];
    }
  }
}

namespace {

ContactVec at3(const double* d) {
  return {d[0], d[1], d[2]};
}

}  // namespace

Vec3 MpmSolver::contact_normal_at(size_t i) const {
  const ContactVec none{0.0, 0.0, 0.0};
  if (opt_.contact == ContactField::kSurfaceFromOwnMass) {
    return contact_normal(at3(&mass_gradient_[3 * i]), none);
  }
  return contact_normal(none, at3(&other_gradient_[3 * i]));
}

Vec3 MpmSolver::contact_impulse_at(size_t i, double advance) const {
  const Lanes8& r = sums_[i].lanes;
  const double* o = &other_sums_[i * sums::kStride];
  const double m = r[sums::kMass], mo = o[sums::kMass];
  if (!(m > 0.0) || !(mo > 0.0)) return {0.0, 0.0, 0.0};
  ContactVec p{}, po{};
  for (size_t a = 0; a < 3; ++a) {
    p[a] = r[sums::kMomentum + a] + advance * r[sums::kForce + a];
    po[a] = o[sums::kMomentum + a] + advance * o[sums::kForce + a];
  }
  return frictionless_contact_impulse(m, p, mo, po, contact_normal_at(i));
}

// Each field's momentum after the step's forces meets the other's; the
// impulse goes on the force, so that the update and the FLIP acceleration
// both see it.
void MpmSolver::contact_on_forces(double dt) {
  const double dt_kf = dt * opt_.units.force_per_mass_to_accel;
  for (size_t i = 0; i < sums_.size(); ++i) {
    const ContactVec j = contact_impulse_at(i, dt_kf);
    for (size_t a = 0; a < 3; ++a) sums_[i].lanes[sums::kForce + a] += j[a] / dt_kf;
  }
}

void MpmSolver::contact_on_remap() {
  for (size_t i = 0; i < sums_.size(); ++i) {
    const ContactVec j = contact_impulse_at(i, 0.0);
    for (size_t a = 0; a < 3; ++a) sums_[i].lanes[sums::kMomentum + a] += j[a];
  }
}

// Nodal momentum update (s-5, s-6). Constrained components are imposed on
// the new velocity, and the acceleration is taken from the constrained
// change, so that FLIP and PIC both honour the constraint.
void MpmSolver::update_nodes(const BoundaryConditions& bc, double dt) {
  enter(Phase::kUpdateNodes);
  if (opt_.contact != ContactField::kNone) contact_on_forces(dt);
  const double kf = opt_.units.force_per_mass_to_accel;
  for (size_t i = 0; i < sums_.size(); ++i) {
    const Lanes8& r = sums_[i].lanes;
    const double mass = r[sums::kMass];
    node_force_[i] = lanes3(r, sums::kForce);
    if (mass > mass_floor_) {
      const double inv = 1.0 / mass;
      const Vec3 v_old = inv * lanes3(r, sums::kMomentum);
      velocity_[i] = v_old;
      add_scaled(velocity_[i], dt * kf * inv, node_force_[i]);
      acceleration_[i] = v_old;  // completed below
    } else {
      velocity_[i] = acceleration_[i] = {0.0, 0.0, 0.0};
    }
  }
  constraint_impulse_ = node_constraint_impulse(bc, outer_face_push_);
  apply_node_constraints(bc, velocity_, true);
  hold_rigid_nodes(bc, dt);
  for (size_t i = 0; i < sums_.size(); ++i) {
    if (sums_[i].lanes[sums::kMass] > mass_floor_) {
      for (size_t a = 0; a < 3; ++a)
        acceleration_[i][a] = (velocity_[i][a] - acceleration_[i][a]) / dt;
    }
  }
}

// Nodes of a prescribed-velocity group move at its velocity; the force
// that holds each there, counted once per node over all ranks, is the
// group's reaction. Also the group's share of the nodes' momentum before
// the hold (held_share_momentum).
void MpmSolver::hold_rigid_nodes(const BoundaryConditions& bc, double dt) {
  const double kf = opt_.units.force_per_mass_to_accel;
  reaction_.assign(bc.point_velocities.size(), {0.0, 0.0, 0.0});
  share_momentum_.assign(bc.point_velocities.size(), {0.0, 0.0, 0.0});
  for (size_t c = 0; c < bc.point_velocities.size(); ++c) {
    const auto& pv = bc.point_velocities[c];
    for (size_t i = 0; i < sums_.size(); ++i) {
      if (rigid_[c][i] <= 0.0) continue;
      // acceleration_ still holds the velocity before the update; rigid_
      // holds each node's whole sum on every copy (sum_rigid).
      if (unique_node_[i]) add_scaled(share_momentum_[c], rigid_[c][i], acceleration_[i]);
      const double mass = sums_[i].lanes[sums::kMass];
      for (size_t a = 0; a < 3; ++a) {
        if (!pv.axis[a]) continue;
        if (unique_node_[i] && mass > mass_floor_) {
          reaction_[c][a] += mass * (pv.velocity[a] - velocity_[i][a]) / (dt * kf);
        }
        velocity_[i][a] = pv.velocity[a];
      }
    }
  }
}

double MpmSolver::held_mass(size_t c) const {
  double m = 0.0;
  for (size_t i = 0; i < sums_.size(); ++i) {
    const double mass = sums_[i].lanes[sums::kMass];
    if (rigid_[c][i] > 0.0 && unique_node_[i] && mass > mass_floor_) m += mass;
  }
  return m;
}

void MpmSolver::shift_held_nodes(const BoundaryConditions& bc, size_t c, const Vec3& dv,
                                 double dt) {
  const double kf = opt_.units.force_per_mass_to_accel;
  Vec3 held_dv{};  // dv on the axes the entry holds
  for (size_t a = 0; a < 3; ++a) held_dv[a] = bc.point_velocities[c].axis[a] ? dv[a] : 0.0;
  double moved = 0.0;  // the reaction's change: the held mass times dv / dt
  for (size_t i = 0; i < sums_.size(); ++i) {
    if (rigid_[c][i] <= 0.0) continue;
    const double mass = sums_[i].lanes[sums::kMass];
    add_scaled(velocity_[i], 1.0, held_dv);
    if (mass > mass_floor_) {
      add_scaled(acceleration_[i], 1.0 / dt, held_dv);
      if (unique_node_[i]) moved += mass;
    }
  }
  add_scaled(reaction_[c], moved / (dt * kf), held_dv);
}

int MpmSolver::held_axes(const BoundaryConditions& bc, size_t i) const {
  int axes = 0;
  for (size_t c = 0; c < bc.point_velocities.size(); ++c) {
    if (rigid_[c][i] <= 0.0) continue;
    for (size_t a = 0; a < 3; ++a) {
      if (bc.point_velocities[c].axis[a]) axes |= 1 << a;
    }
  }
  return axes;
}

void MpmSolver::held_nodes(const BoundaryConditions& bc, double* records) const {
  for (size_t i = 0; i < sums_.size(); ++i) {
    double* r = records + i * kHeldStride;
    const int axes = held_axes(bc, i);
    r[0] = axes;
    for (size_t a = 0; a < 3; ++a) r[1 + a] = (axes & (1 << a)) != 0 ? velocity_[i][a] : 0.0;
  }
}

void MpmSolver::mark_held_nodes(const BoundaryConditions& bc) {
  if (bc.point_velocities.empty()) return;
  for (size_t i = 0; i < sums_.size(); ++i) sums_[i].lanes[sums::kHeldAxes] = held_axes(bc, i);
}

void MpmSolver::hold_nodes_of_others(const double* records, double dt) {
  others_held_.clear();
  for (size_t i = 0; i < sums_.size(); ++i) {
    const double* r = records + i * kHeldStride;
    const auto axes = static_cast<int>(std::lround(r[0]));
    if (axes == 0) continue;
    const bool moving = sums_[i].lanes[sums::kMass] > mass_floor_;
    for (size_t a = 0; a < 3; ++a) {
      if ((axes & (1 << a)) == 0) continue;
      if (moving) acceleration_[i][a] += (r[1 + a] - velocity_[i][a]) / dt;
      velocity_[i][a] = r[1 + a];
      others_held_.push_back({i, a, r[1 + a]});
    }
  }
}

// Grid to points (s-7), and under update-stress-last the remap of the new
// point momenta with this step's shape functions (s-10) in the same pass.
void MpmSolver::map_to_points(MaterialPoints& points, const BoundaryConditions& bc, double dt) {
  enter(Phase::kMapToPoints);
  if (!opt_.material_flip.empty() || !opt_.material_density_from_grid.empty()) {
    with_eval([&](const auto& eval) { own_material_fields(eval, points, dt); });
  }
  pack_kinematics(acceleration_, velocity_);
  const Lanes8 keep_all_but_momentum = {1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0};
  for (auto& r : sums_) r.lanes *= keep_all_but_momentum;
  with_eval([&](const auto& eval) { grid_to_points(eval, points, bc, dt); });
}

// Two corrections of materials that keep their own nodal field
// (SolverOptions::material_flip, material_density_from_grid), from the
// nodes' sums of this step, before the grid's update reaches the points.
//
// A blend f < 1 moves each point's velocity (1 - f) of the way to its own
// material's nodal field there, sum_i N_i (sum_q N_iq m_q v_q / sum_q N_iq
// m_q) over that material's points q. The PIC part of a FLIP/PIC blend
// would use every material's field, which at a node shared with another
// material moves momentum between them; this keeps each material's momentum
// exactly (the N_i sum to one) and still damps the point velocities the grid
// does not see.
//
// A density from the grid is sum_i N_i m_i / sum_i N_i V_i, with m_i the
// material's nodal mass and V_i the nodal volume less what the nodes' other
// mass fills at SolverOptions::filler_density.
template <class Eval>
void MpmSolver::own_material_fields(const Eval& eval, MaterialPoints& points, double dt) {
  const size_t n = points.size();
  std::vector<double> field(4 * sums_.size(), 0.0);  // per node: m, m v
  const auto own = [&](size_t p) {
    return opt_.flip_of(points.material[p]) < 1.0 || opt_.density_from_grid(points.material[p]);
  };
  for (size_t p = 0; p < n; ++p) {
    if (!own(p)) continue;
    const auto& s = locate(eval, points, p);
    for (int q = 0; q < s.count; ++q) {
      double* f = &field[4 * static_cast<size_t>(s.node[static_cast<size_t>(q)])];
      const double w = s.N[static_cast<size_t>(q)] * points.mass[p];
      f[0] += w;
      for (size_t a = 0; a < 3; ++a) f[1 + a] += w * points.v[p][a];
    }
  }
  if (patch_.sum_shared) patch_.sum_shared(field.data(), 4, 4);
  for (size_t p = 0; p < n; ++p) {
    if (!own(p)) continue;
    const auto& s = locate(eval, points, p);
    Vec3 v{0.0, 0.0, 0.0};
    double mass = 0.0, free_volume = 0.0;
    for (int q = 0; q < s.count; ++q) {
      const auto i = static_cast<size_t>(s.node[static_cast<size_t>(q)]);
      const double* f = &field[4 * i];
      const double N = s.N[static_cast<size_t>(q)];
      if (!(f[0] > 0.0)) continue;
      for (size_t a = 0; a < 3; ++a) v[a] += N / f[0] * f[1 + a];
      if (!opt_.density_from_grid(points.material[p])) continue;
      const double rest = sums_[i].lanes[sums::kMass] - f[0] + other_mass(i);
      const double filled = std::max(0.0, rest) / opt_.filler_density;
      mass += N * f[0];
      free_volume += N * std::max(0.0, nodal_volume(i) - filled);
    }
    const double keep = opt_.flip_of(points.material[p]);
    for (size_t a = 0; a < 3; ++a) points.v[p][a] += (1.0 - keep) * (v[a] - points.v[p][a]);
    if (opt_.density_from_grid(points.material[p])) {
      take_grid_density(points, p, mass, free_volume, dt);
    }
  }
}

double MpmSolver::nodal_volume(size_t i) const {
  const auto ijk = patch_.nodes.ijk_of_local(static_cast<std::int64_t>(i));
  const double h = patch_.domain.cell_size();
  double v = h * h * h;
  for (size_t a = 0; a < 3; ++a) {
    if (patch_.periodic[a]) continue;
    if (ijk[a] == 0 || ijk[a] == patch_.domain.cells()[a]) v *= 0.5;
  }
  return v;
}

// Compresses point p isotropically from its density to the grid's, as one
// step of the isotropic velocity gradient that makes that change: the
// material's own update then does the work (an ideal gas's adiabatic de =
// -P dv) and F follows, so that the point's volume is its mass over the new
// density.
void MpmSolver::take_grid_density(MaterialPoints& points, size_t p, double gas_mass,
                                  double free_volume, double dt) const {
  // A point among nodes the other material fills keeps its own density.
  if (!(free_volume > 0.05 * std::pow(patch_.domain.cell_size(), 3))) return;
  MaterialPointState& st = points.state[p];
  const double target =
      st.density + opt_.grid_density_weight * (gas_mass / free_volume - st.density);
  const double stretch = std::cbrt(st.density / target);  // per axis
  const Mat3 L = ((stretch - 1.0) / dt) * Mat3::Identity();
  points.F[p] *= stretch;
  st.density = target;
  materials_[static_cast<size_t>(points.material[p])]->update(L, dt, st);
}

template <class Eval>
void MpmSolver::grid_to_points(const Eval& eval, MaterialPoints& points,
                               const BoundaryConditions& bc, double dt) {
  const size_t n = points.size();
  const bool last = opt_.stress_update == StressUpdate::kLast;
  const bool prescribed = !bc.point_velocities.empty();
  const double flip = opt_.flip;
  size_t first = 0;
  if constexpr (std::is_same_v<Eval, LinearEval>) {
    for (; first + kLanes <= n; first += kLanes)
      grid_to_points_lanes(eval.kernel, points, bc, first, dt);
  }
  for (size_t p = first; p < n; ++p) {
    const auto& s = locate(eval, points, p);
    Lanes8 k{};  // lanes 0-2 acceleration, 3-5 velocity
    for (int q = 0; q < s.count; ++q) {
      const auto qq = static_cast<size_t>(q);
      k += s.N[qq] * kin_[static_cast<size_t>(s.node[qq])].lanes;
    }
    Vec3& vp = points.v[p];
    for (int a = 0; a < 3; ++a) {
      vp[static_cast<size_t>(a)] =
          flip * (vp[static_cast<size_t>(a)] + dt * k[a]) + (1.0 - flip) * k[a + 3];
    }
    if (prescribed) hold_prescribed(points, bc, p, vp);
    if (last) {
      const double m = points.mass[p];
      const Lanes8 pm = {0.0, m * vp[0], m * vp[1], m * vp[2], 0.0, 0.0, 0.0, 0.0};
      for (int q = 0; q < s.count; ++q) {
        const auto qq = static_cast<size_t>(q);
        sums_[static_cast<size_t>(s.node[qq])].lanes += s.N[qq] * pm;
      }
    } else {
      Vec3 vel = lanes3(k, 3);
      if (prescribed) hold_prescribed(points, bc, p, vel);
      move_point(points, p, vel, dt);  // s-8
    }
  }
}

void MpmSolver::complete_remap_sums() {
  enter(Phase::kCompleteRemapSums);
  if (opt_.stress_update == StressUpdate::kLast) sum_shared(sums::kMomentum, 3);
}

// Stress update (s-11 to s-14) at the positions the step started from,
// then the move with the momentum-update velocity (s-8), a block of points
// at a time: the kinematics point by point from the grid, then the stress
// update across the block's points, then the move. Under
// update-stress-first the points have moved already.
void MpmSolver::update_stress_and_move(MaterialPoints& points, const BoundaryConditions& bc,
                                       double dt) {
  update_stress_and_map_midpoints(points, bc, dt);
  complete_midpoint_sums();
  move_from_midpoints(points, bc, dt);
}

void MpmSolver::update_stress_and_map_midpoints(MaterialPoints& points,
                                                const BoundaryConditions& bc, double dt) {
  enter(Phase::kUpdateStress);
  if (opt_.stress_update != StressUpdate::kLast) return;
  if (opt_.contact != ContactField::kNone) contact_on_remap();
  nodal_velocities(bc, remap_velocity_);  // s-11
  impose_rigid(bc, remap_velocity_);
  for (const OtherHold& h : others_held_) remap_velocity_[h.node][h.axis] = h.velocity;
  if (opt_.ddmp) nodal_gradient(remap_velocity_, G_);
  if (opt_.move == PointMove::kMidpoint) {
    // The stress is updated at the start; the move is made in
    // move_from_midpoints, its first half here with the remapped velocity,
    // so that the midpoint is where the points' new momentum carries them.
    start_positions_ = points.x;
    pack_kinematics(remap_velocity_, remap_velocity_);
    with_eval([&](const auto& eval) {
      stress_and_move(eval, points, bc, dt, 0.0);
      map_at_midpoints(eval, points, bc, dt);
    });
    midpoint_pending_ = true;
    return;
  }
  pack_kinematics(remap_velocity_, velocity_);
  with_eval([&](const auto& eval) { stress_and_move(eval, points, bc, dt, dt); });
}

void MpmSolver::complete_midpoint_sums() {
  if (midpoint_pending_) sum_shared(sums::kMass, 4);
}

void MpmSolver::move_from_midpoints(MaterialPoints& points, const BoundaryConditions& bc,
                                    double dt) {
  if (!midpoint_pending_) return;
  midpoint_pending_ = false;
  // The two fields meet again at the midpoints, along the normal of the
  // step's start (the other field's midpoint mass and momentum are in
  // other_sums_ by now).
  if (opt_.contact != ContactField::kNone) contact_on_remap();
  nodal_velocities(bc, remap_velocity_);
  impose_rigid(bc, remap_velocity_);
  for (const OtherHold& h : others_held_) remap_velocity_[h.node][h.axis] = h.velocity;
  with_eval([&](const auto& eval) { move_with_midpoint_velocity(eval, points, bc, dt); });
}

// The weights at a midpoint are those of the cell it stands in. One that
// stands past this rank's box (its point crosses into another rank's cells
// this step, and migrates before the next) takes them at the box's face:
// the one place where ranks change more than round-off (1e-5 Å in 250 steps
// of tests/integration/configs/dpd_grid_ranks.yaml on 4 ranks). Weights
// extended from the start cell instead would keep ranks exact, but a
// crystal whose particles sit on nodes then gained 2.4 eV in 10 ps.
template <class Eval>
auto MpmSolver::midpoint_stencil(const Eval& eval, const MaterialPoints& points, size_t p) const {
  const auto& lo = local_.origin();
  const auto& hi = local_.upper();
  Vec3 x = points.x[p];
  for (size_t a = 0; a < 3; ++a) x[a] = std::clamp(x[a], lo[a], hi[a]);
  return eval(x);
}

template <class Stencil>
Vec3 MpmSolver::remapped_velocity(const Stencil& s) const {
  Vec3 vel{0.0, 0.0, 0.0};
  for (int q = 0; q < s.count; ++q) {
    const auto qq = static_cast<size_t>(q);
    add_scaled(vel, s.N[qq], remap_velocity_[static_cast<size_t>(s.node[qq])]);
  }
  return vel;
}

// PointMove::kMidpoint's first half: each point moves half a step with the
// remapped velocity at its start, and its mass and momentum are mapped
// there, replacing the step's mass and momentum sums (this rank's part).
template <class Eval>
void MpmSolver::map_at_midpoints(const Eval& eval, MaterialPoints& points,
                                 const BoundaryConditions& bc, double dt) {
  const size_t n = points.size();
  const bool prescribed = !bc.point_velocities.empty();
  for (size_t p = 0; p < n; ++p) {
    Vec3 vel = remapped_velocity(eval(start_positions_[p]));
    if (prescribed) hold_prescribed(points, bc, p, vel);
    move_point(points, p, vel, 0.5 * dt);
  }
  const Lanes8 keep_all_but_mass_and_momentum = {0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0};
  for (auto& r : sums_) r.lanes *= keep_all_but_mass_and_momentum;
  for (size_t p = 0; p < n; ++p) {
    const auto& s = midpoint_stencil(eval, points, p);
    const double m = points.mass[p];
    const Vec3& v = points.v[p];
    const Lanes8 pm = {m, m * v[0], m * v[1], m * v[2], 0.0, 0.0, 0.0, 0.0};
    for (int q = 0; q < s.count; ++q) {
      const auto qq = static_cast<size_t>(q);
      sums_[static_cast<size_t>(s.node[qq])].lanes += s.N[qq] * pm;
    }
  }
}

// Its second half, once the midpoint sums are whole: each point moves a
// whole step from its start with the grid velocity at its midpoint.
template <class Eval>
void MpmSolver::move_with_midpoint_velocity(const Eval& eval, MaterialPoints& points,
                                            const BoundaryConditions& bc, double dt) {
  const size_t n = points.size();
  const bool prescribed = !bc.point_velocities.empty();
  for (size_t p = 0; p < n; ++p) {
    Vec3 vel = remapped_velocity(midpoint_stencil(eval, points, p));
    if (prescribed) hold_prescribed(points, bc, p, vel);
    points.x[p] = start_positions_[p];
    move_point(points, p, vel, dt);
  }
}

template <class Eval>
void MpmSolver::stress_and_move(const Eval& eval, MaterialPoints& points,
                                const BoundaryConditions& bc, double dt, double move_dt) {
  const size_t n = points.size();
  const bool prescribed = !bc.point_velocities.empty();
  constexpr size_t kBlock = MaterialBlock::kSize;
  MaterialBlock& block = *block_;
  Mat3 L;
  std::array<Vec3, kBlock> vb;
  for (size_t p0 = 0; p0 < n; p0 += kBlock) {
    const size_t m = std::min(kBlock, n - p0);
    size_t i = 0;
    if constexpr (std::is_same_v<Eval, LinearEval>) {
      if (!opt_.ddmp) {
        for (; i + kLanes <= m; i += kLanes)
          point_kinematics_lanes(eval.kernel, points, p0 + i, block, i, &vb[i]);
      }
    }
    for (; i < m; ++i) {
      decltype(auto) s = locate(eval, points, p0 + i);
      keep_weights_in_memory(s);
      point_kinematics(points, p0 + i, s, L, vb[i]);
      block.set_velocity_gradient(i, L);
    }
    update_stress_block(points, p0, m, block, dt);
    for (size_t i = 0; i < m; ++i) {
      if (prescribed) hold_prescribed(points, bc, p0 + i, vb[i]);
      move_point(points, p0 + i, vb[i], move_dt);
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

}  // namespace pbms::grid
