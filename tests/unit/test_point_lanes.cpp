// The grid step's SIMD passes against its point-by-point path, at the SIMD
// width this file is compiled for. pbms_unit_tests runs them at the native
// width; point_lanes_tests_<set> runs them with the grid step, the
// materials and this file built for each instruction set the machine runs
// (x86-64-v4, x86-64-v3, x86-64: 8, 4 and 2 points at once), so that every
// width is checked wherever the tests run (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "materials/material_registry.hpp"
#include "pbms/grid/mpm_solver.hpp"
#include "pbms/grid/shape_function.hpp"
#include "pbms/grid/shape_function_linear.hpp"
#include "pbms/simd/point_lanes.hpp"
#include "points_in_cells.hpp"

using namespace pbms;
using namespace pbms::grid;
using pbms::mpm::MaterialRegistry;

namespace {

constexpr int kW = simd::kPointLanes;

// The linear functions behind the general interface: the solver then takes
// its point-by-point path with ShapeFunction::evaluate.
struct LinearBehindTheInterface final : ShapeFunction {
  void evaluate(const RegularGrid& g, const std::array<double, 3>& x,
                ShapeStencil& out) const override {
    ShapeFunctionRegistry::create("linear")->evaluate(g, x, out);
  }
  int support_nodes() const override { return 8; }
  std::string_view name() const override { return "linear-behind-the-interface"; }
};

struct MaterialCase {
  std::string style;
  mpm::MaterialParameters params;
  double density, pressure;
  bool walled;  // held in a box of node walls (a gas would escape)
};

}  // namespace

// The solver compiled into this binary runs the width this file was
// compiled for: a variant test links the variant's grid step, not the
// native one.
TEST(PointLanes, SolverRunsThisBuildsWidth) {
  const auto width = MpmSolver::simd_width();
  EXPECT_EQ(width.lanes, kW) << width.isa;
  EXPECT_EQ(std::string(width.isa), simd::kPointLanesIsa);
}

// The W-points-at-once evaluation gives each lane exactly the single-point
// stencil (the passes rely on it to match the point-by-point code): random
// points, plus points on cell faces, on nodes and on the grid's upper faces.
TEST(PointLanes, StencilEqualsThePointStencilBitForBit) {
  // Off-origin, non-unit and anisotropic, so that index mistakes show.
  const RegularGrid g({-1.3, 2.1, 0.7}, 0.37, {7, 5, 6});
  const ShapeFunctionLinear::Kernel kernel(g);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> xs;
  for (int i = 0; i < 4000; ++i) {
    Vec3 x{};
    for (size_t d = 0; d < 3; ++d) x[d] = g.origin()[d] + u(rng) * (g.upper()[d] - g.origin()[d]);
    xs.push_back(x);
  }
  const auto& o = g.origin();
  const double h = g.cell_size();
  const auto c = g.cells();
  for (int i = 0; i <= c[0]; ++i) {
    xs.push_back({o[0] + i * h, o[1] + 0.5 * h, o[2] + c[2] * h});  // faces, the top face
    xs.push_back({o[0] + i * h, o[1] + c[1] * h, o[2]});            // nodes on the upper edge
  }
  while (xs.size() % kW != 0) xs.push_back(xs[xs.size() % 7]);
  for (size_t p = 0; p < xs.size(); p += kW) {
    double column[3][kW];
    simd::Lanes<kW> x[3];
    for (size_t d = 0; d < 3; ++d) {
      for (size_t k = 0; k < kW; ++k) column[d][k] = xs[p + k][d];
      x[d] = simd::load_lanes<kW>(column[d]);
    }
    LinearStencilLanes<kW> lanes;
    kernel(x, lanes);
    for (size_t k = 0; k < kW; ++k) {
      LinearStencil one;
      kernel(xs[p + k], one);
      for (int q = 0; q < 8; ++q) {
        ASSERT_EQ(lanes.node(k, q), one.node[static_cast<size_t>(q)]);
        simd::Lanes<kW> dn[3];
        lanes.dN(q, dn);
        // Bitwise: the same operations in the same order.
        ASSERT_EQ(lanes.N(q)[k], one.N[q]) << "point " << p + k;
        ASSERT_EQ(dn[0][k], one.dNx[q]);
        ASSERT_EQ(dn[1][k], one.dNy[q]);
        ASSERT_EQ(dn[2][k], one.dNz[q]);
      }
    }
  }
}

// The linear style runs its passes W points at a time across SIMD lanes;
// any other style goes point by point through ShapeFunction::evaluate. The
// same linear functions behind the general interface must give the same
// trajectory to round-off, for each kind of material (elastic, J2 with
// plastic flow, ideal gas), with every optional term of a step: both
// stress updates, a FLIP/PIC blend, body force, a point load, a rigid
// group and a node constraint. Without the loads and the rigid group the
// P2G pass also runs across lanes; a point count that is not a multiple of
// the width leaves a tail for the point-by-point code.
class SolverPassesAcrossLanes : public testing::TestWithParam<MaterialCase> {};

TEST_P(SolverPassesAcrossLanes, MatchThePointByPointPath) {
  const MaterialCase& mc = GetParam();
  const auto materials = [&] {
    std::vector<std::unique_ptr<Material>> m;
    m.push_back(MaterialRegistry::create(mc.style, mc.params));
    return m;
  };
  const MaterialPointState s0 = materials()[0]->initial_state(mc.density, mc.pressure);
  for (const bool loads : {true, false})
    for (const auto update : {StressUpdate::kLast, StressUpdate::kFirst}) {
      RegularGrid g({0, 0, 0}, 1.0, {8, 7, 6});
      SolverOptions opt;
      opt.stress_update = update;
      opt.flip = 0.9;
      MpmSolver lanes(g, ShapeFunctionRegistry::create("linear"), materials(), opt);
      MpmSolver general(g, std::make_unique<LinearBehindTheInterface>(), materials(), opt);
      MaterialPoints a;
      test::fill_cells(a, g, {1, 1, 1}, {7, 6, 5}, 2, s0);
      for (size_t p = 0; p < a.size(); ++p) {
        const auto& x = a.x[p];
        a.v[p] = {0.3 * std::sin(0.7 * x[1]), 0.2 * std::cos(0.5 * x[0] + x[2]), 0.1 * x[0]};
        a.groups[p] = (x[0] < 2 ? 1u : 0u) | (x[2] > 4 ? 2u : 0u);
      }
      for (const size_t p : {700, 333, 5}) a.erase(p);
      ASSERT_NE(a.size() % kW, 0u);
      MaterialPoints b = a;
      BoundaryConditions bc;
      if (loads) {
        bc.body_acceleration = {0.0, 0.0, -0.05};
        bc.loads.push_back({2u, {0.01, 0.0, 0.02}});
        bc.point_velocities.push_back({1u, {true, false, false}, {0.05, 0.0, 0.0}});
      }
      bc.nodes.push_back({{{0, 0, 0}, {9, 8, 1}}, {false, false, true}, {0, 0, 0}});
      if (mc.walled) {
        // The node planes on the body's faces: x = 1, 7; y = 1, 6; z = 1, 5.
        for (const int x : {1, 7})
          bc.nodes.push_back({{{x, 0, 0}, {x + 1, 8, 7}}, {true, false, false}, {}});
        for (const int y : {1, 6})
          bc.nodes.push_back({{{0, y, 0}, {9, y + 1, 7}}, {false, true, false}, {}});
        for (const int z : {1, 5})
          bc.nodes.push_back({{{0, 0, z}, {9, 8, z + 1}}, {false, false, true}, {}});
      }
      const double dt = 0.2 * lanes.stable_time_step(a);
      for (int step = 0; step < 40; ++step) {
        lanes.step(a, bc, dt);
        general.step(b, bc, dt);
      }
      double dx = 0, dv = 0, ds = 0, smax = 0, plastic = 0, dplastic = 0;
      for (size_t p = 0; p < a.size(); ++p) {
        for (size_t c = 0; c < 3; ++c) {
          dx = std::max(dx, std::abs(a.x[p][c] - b.x[p][c]));
          dv = std::max(dv, std::abs(a.v[p][c] - b.v[p][c]));
        }
        for (int c = 0; c < 6; ++c) {
          ds = std::max(ds, std::abs(a.state[p].stress[c] - b.state[p].stress[c]));
          smax = std::max(smax, std::abs(a.state[p].stress[c]));
        }
        plastic = std::max(plastic, a.state[p].plastic_strain);
        dplastic =
            std::max(dplastic, std::abs(a.state[p].plastic_strain - b.state[p].plastic_strain));
      }
      SCOPED_TRACE(mc.style + (loads ? ", loads" : "") +
                   (update == StressUpdate::kLast ? ", USL" : ", USF"));
      EXPECT_GT(smax, 1e-2);  // the run did deform the body
      if (mc.style == "j2_plasticity") {
        EXPECT_GT(plastic, 0.0);  // and it flowed
      }
      EXPECT_LT(dx, 1e-12);
      EXPECT_LT(dv, 1e-12);
      EXPECT_LT(ds, 1e-11 * smax);
      EXPECT_LE(dplastic, 1e-11 * std::max(plastic, 1e-300));
    }
}

INSTANTIATE_TEST_SUITE_P(
    Materials, SolverPassesAcrossLanes,
    testing::Values(
        MaterialCase{
            "linear_elastic", {{"youngs_modulus", 200.0}, {"poisson_ratio", 0.3}}, 1.0, 0.0, false},
        MaterialCase{"j2_plasticity",
                     {{"youngs_modulus", 200.0},
                      {"poisson_ratio", 0.3},
                      {"yield_stress", 0.5},
                      {"hardening_modulus", 5.0}},
                     1.0,
                     0.0,
                     false},
        MaterialCase{"ideal_gas", {{"gamma", 1.4}}, 1.0, 1.0, true}),
    [](const testing::TestParamInfo<MaterialCase>& info) { return info.param.style; });
