// The phased MPM step: two solvers on one grid that add each other's nodal
// sums between the phases advance a body exactly as one solver holding all
// its points does (the in-process form of the nodal sum across programs).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "materials/material_registry.hpp"
#include "pbms/error.hpp"
#include "pbms/grid/mpm_solver.hpp"
#include "pbms/grid/shape_function.hpp"
#include "pbms/grid/stressless_particle.hpp"

using namespace pbms;
using namespace pbms::mpm;
using namespace pbms::grid;

namespace {

std::unique_ptr<MpmSolver> elastic_solver(const grid::RegularGrid& g, const SolverOptions& opt) {
  std::vector<std::unique_ptr<Material>> m;
  m.push_back(MaterialRegistry::create("linear_elastic",
                                       {{"youngs_modulus", 200.0}, {"poisson_ratio", 0.3}}));
  return std::make_unique<MpmSolver>(g, grid::ShapeFunctionRegistry::create("linear"), std::move(m),
                                     opt);
}

// Two points per cell edge in cells [1, 7) x [1, 5) x [1, 5), moving with a
// shear-and-stretch velocity field, so that every term of the step is busy.
MaterialPoints body(const grid::RegularGrid& g) {
  MaterialPoints pts;
  const double h = g.cell_size();
  for (int k = 2; k < 10; ++k)
    for (int j = 2; j < 10; ++j)
      for (int i = 2; i < 14; ++i) {
        MaterialPointState s;
        s.density = 1.0;
        const Vec3 x{h * (i + 0.5) / 2, h * (j + 0.5) / 2, h * (k + 0.5) / 2};
        pts.add(static_cast<int64_t>(pts.size()), x, std::pow(h / 2, 3), s, 0);
        pts.v.back() = {0.02 * std::sin(x[0]), 0.01 * x[2], -0.015 * std::cos(x[1])};
      }
  return pts;
}

// The points of `all` that `keep` selects, as a set of their own.
MaterialPoints subset(const MaterialPoints& all, bool (*keep)(const Vec3&)) {
  MaterialPoints out;
  for (size_t p = 0; p < all.size(); ++p) {
    if (!keep(all.x[p])) continue;
    out.add(all.id[p], all.x[p], all.volume0[p], all.state[p], all.material[p], all.groups[p]);
    out.v.back() = all.v[p];
  }
  return out;
}

double norm(const Vec3& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

double max_abs_difference(const Vec3& u, const Vec3& v) {
  return std::max({std::abs(u[0] - v[0]), std::abs(u[1] - v[1]), std::abs(u[2] - v[2])});
}

// Each solver's lanes [first, first + count) become the sum over both.
void add_each_others_sums(MpmSolver& a, MpmSolver& b, int first, int count) {
  const auto sa = a.nodal_sums();
  const auto sb = b.nodal_sums();
  ASSERT_EQ(sa.nodes.count(), sb.nodes.count());
  for (int64_t i = 0; i < sa.nodes.count(); ++i) {
    for (int c = first; c < first + count; ++c) {
      double& x = sa.data[i * sa.stride + c];
      double& y = sb.data[i * sb.stride + c];
      x = y = x + y;
    }
  }
}

}  // namespace

namespace {

// Two solvers that add each other's sums between the phases against one
// that holds every point, both with the point move `move`.
void split_matches_one(PointMove move) {
  const grid::RegularGrid g({0, 0, 0}, 1.0, {8, 6, 6});
  SolverOptions opt;
  opt.flip = 0.95;
  opt.move = move;
  const MaterialPoints all = body(g);
  opt.reference_point_mass = *std::min_element(all.mass.begin(), all.mass.end());
  const BoundaryConditions bc;
  const double dt = 0.02;
  const int steps = 200;

  auto whole = elastic_solver(g, opt);
  MaterialPoints one = all;
  auto left = elastic_solver(g, opt);
  auto right = elastic_solver(g, opt);
  MaterialPoints a = subset(all, [](const Vec3& x) { return x[0] < 4.1; });
  MaterialPoints b = subset(all, [](const Vec3& x) { return x[0] >= 4.1; });
  ASSERT_GT(a.size(), 0u);
  ASSERT_GT(b.size(), 0u);

  for (int n = 0; n < steps; ++n) {
    whole->step(one, bc, dt);
    left->begin_step(a);
    right->begin_step(b);
    left->map_to_grid(a, bc, dt);
    right->map_to_grid(b, bc, dt);
    left->complete_nodal_sums();
    right->complete_nodal_sums();
    add_each_others_sums(*left, *right, sums::kMass, 7);
    left->update_nodes(bc, dt);
    right->update_nodes(bc, dt);
    left->map_to_points(a, bc, dt);
    right->map_to_points(b, bc, dt);
    left->complete_remap_sums();
    right->complete_remap_sums();
    add_each_others_sums(*left, *right, sums::kMomentum, 3);
    left->update_stress_and_map_midpoints(a, bc, dt);
    right->update_stress_and_map_midpoints(b, bc, dt);
    left->complete_midpoint_sums();
    right->complete_midpoint_sums();
    if (move == PointMove::kMidpoint) add_each_others_sums(*left, *right, sums::kMass, 4);
    left->move_from_midpoints(a, bc, dt);
    right->move_from_midpoints(b, bc, dt);
  }

  // Ids index `one`; the split sets only changed the summation order.
  double vmax = 0.0, dx = 0.0, dv = 0.0, ds = 0.0, smax = 0.0;
  for (size_t p = 0; p < one.size(); ++p) {
    vmax = std::max(vmax, norm(one.v[p]));
    smax = std::max(smax, std::abs(one.state[p].stress.voigt[0]));
  }
  for (const MaterialPoints* part : {&a, &b}) {
    for (size_t p = 0; p < part->size(); ++p) {
      const auto id = static_cast<size_t>(part->id[p]);
      dx = std::max(dx, max_abs_difference(part->x[p], one.x[id]));
      dv = std::max(dv, max_abs_difference(part->v[p], one.v[id]));
      ds = std::max(ds, std::abs(part->state[p].stress.voigt[0] - one.state[id].stress.voigt[0]));
    }
  }
  std::printf("split vs one solver after %d steps: max |dx| = %.2e, max |dv| / vmax = %.2e\n",
              steps, dx, dv / vmax);
  // The points moved (the check is not of a body at rest).
  EXPECT_GT(vmax, 1e-3);
  EXPECT_GT(smax, 1e-3);
  // Round-off of a reordered sum, grown over 200 steps: the bounds
  // for the split run across programs (1e-11 of the box, 1e-10 of the
  // largest speed).
  EXPECT_LE(dx, 1e-11 * 8.0);
  EXPECT_LE(dv, 1e-10 * vmax);
  EXPECT_LE(ds, 1e-10 * smax);
}

}  // namespace

TEST(MpmPhases, TwoSolversSummingAcrossEachOtherMatchOneSolver) {
  split_matches_one(PointMove::kStepStart);
}

// The midpoint move's second map (the points' mass and momentum at their
// midpoints) summed across the two as well: the concurrent stage's
// grid.move: midpoint.
TEST(MpmPhases, TwoSolversMovingFromMidpointsMatchOneSolver) {
  split_matches_one(PointMove::kMidpoint);
}

TEST(MpmPhases, APhaseOutOfOrderIsRefused) {
  const grid::RegularGrid g({0, 0, 0}, 1.0, {8, 6, 6});
  auto solver = elastic_solver(g, SolverOptions{});
  MaterialPoints pts = body(g);
  solver->begin_step(pts);
  EXPECT_THROW(solver->update_nodes({}, 0.01), Error);
}

namespace {

// Particles that carry no stress, on a 3-D periodic grid, with random
// velocities: the DPD particles of the DPD/MPM-grid model.
struct ForceDriven {
  std::unique_ptr<MpmSolver> solver;
  MaterialPoints pts;
};

ForceDriven force_driven(const grid::RegularGrid& g) {
  std::vector<std::unique_ptr<Material>> m;
  m.push_back(std::make_unique<StresslessParticle>());
  GridPatch patch = GridPatch::whole(g);
  patch.periodic = {true, true, true};
  SolverOptions opt;
  ForceDriven f{std::make_unique<MpmSolver>(patch, grid::ShapeFunctionRegistry::create("linear"),
                                            std::move(m), opt),
                {}};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    MaterialPointState s;
    s.density = 1.0;
    const Vec3 x{u(rng) * g.upper()[0], u(rng) * g.upper()[1], u(rng) * g.upper()[2]};
    f.pts.add(i, x, 1.0, s, 0);
    f.pts.v.back() = {u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
  }
  return f;
}

Vec3 momentum(const MaterialPoints& pts) {
  Vec3 p{0.0, 0.0, 0.0};
  for (size_t i = 0; i < pts.size(); ++i)
    for (size_t a = 0; a < 3; ++a) p[a] += pts.mass[i] * pts.v[i][a];
  return p;
}

}  // namespace

// A force proportional to each particle's mass accelerates every particle
// alike through the grid: v = v0 + a t for each, exactly as for a free
// particle (the nodal acceleration is a at every node holding mass).
TEST(MpmPointForces, AUniformFieldAcceleratesEveryParticleAlike) {
  const grid::RegularGrid g({0, 0, 0}, 1.0, {5, 5, 5});
  auto f = force_driven(g);
  const Vec3 a{0.3, -0.2, 0.1};
  std::vector<Vec3> force(f.pts.size());
  const MaterialPoints start = f.pts;
  const double dt = 0.01;
  const int steps = 100;
  BoundaryConditions bc;
  for (int n = 0; n < steps; ++n) {
    for (size_t i = 0; i < f.pts.size(); ++i)
      for (size_t c = 0; c < 3; ++c) force[i][c] = f.pts.mass[i] * a[c];
    bc.point_forces = force;
    f.solver->step(f.pts, bc, dt);
  }
  double worst = 0.0;
  for (size_t i = 0; i < f.pts.size(); ++i)
    for (size_t c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(f.pts.v[i][c] - (start.v[i][c] + steps * dt * a[c])));
  EXPECT_LT(worst, 1e-12);
}

// Pair forces, equal and opposite, change no total momentum through the
// grid: sum_p m_p dv_p = dt sum_I f_I = dt sum_p F_p = 0 when every node
// holding mass is above the floor.
TEST(MpmPointForces, PairForcesKeepTheTotalMomentum) {
  const grid::RegularGrid g({0, 0, 0}, 1.0, {5, 5, 5});
  auto f = force_driven(g);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> force(f.pts.size());
  const Vec3 p0 = momentum(f.pts);
  BoundaryConditions bc;
  for (int n = 0; n < 200; ++n) {
    std::fill(force.begin(), force.end(), Vec3{0.0, 0.0, 0.0});
    for (size_t i = 0; i + 1 < force.size(); i += 2) {
      const Vec3 fij{u(rng), u(rng), u(rng)};
      for (size_t c = 0; c < 3; ++c) {
        force[i][c] += fij[c];
        force[i + 1][c] -= fij[c];
      }
    }
    bc.point_forces = force;
    f.solver->step(f.pts, bc, 0.01);
  }
  const Vec3 p = momentum(f.pts);
  double scale = 0.0;
  for (size_t i = 0; i < f.pts.size(); ++i) scale += f.pts.mass[i] * norm(f.pts.v[i]);
  EXPECT_GT(scale, 0.0);
  for (size_t c = 0; c < 3; ++c) EXPECT_LT(std::abs(p[c] - p0[c]), 1e-13 * scale) << c;
}
