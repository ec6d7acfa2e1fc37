// Throughput of the MPM step on one core: a 3-D elastic block of 50^3
// cells with 2 x 2 x 2 points per cell (1,000,000 points), linear shape
// functions, 100 update-stress-last FLIP steps of a standing wave (the
// faster of two rounds).
//
// Prints BENCH mpm_particle_steps_per_s and BENCH mpm_roofline_fraction:
// the bytes the three particle passes and the grid passes must move per
// step (each array they read or write once, counted below), divided by the
// time, over a STREAM triad bandwidth measured in the same process.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "materials/material_registry.hpp"
#include "pbms/grid/mpm_solver.hpp"
#include "pbms/grid/shape_function.hpp"

using namespace pbms;
using namespace pbms::mpm;
using namespace pbms::grid;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// STREAM triad a = b + s c on arrays far larger than the caches; the best
// of several repetitions, counting 3 x 8 bytes per element (24 with the
// write-allocate of a left out, as STREAM reports it).
double stream_triad_bytes_per_s() {
  const size_t n = 40'000'000;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  double best = 1e30;
  for (int rep = 0; rep < 6; ++rep) {
    const auto t0 = Clock::now();
    const double s = 3.0 + rep;
    for (size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    best = std::min(best, seconds_since(t0));
  }
  volatile double sink = a[n / 2];
  (void)sink;
  return 24.0 * static_cast<double>(n) / best;
}

// Seconds spent in each pass of the step over a round.
struct PassTimes {
  double p2g = 0.0;     // map_to_grid: the points' mass, momentum and forces to the nodes
  double grid = 0.0;    // begin_step, the node sums' completion and the node update
  double g2p = 0.0;     // map_to_points: new point velocities and the momentum remap
  double stress = 0.0;  // update_stress_and_move: gradient, stress update, move
  [[nodiscard]] double total() const { return p2g + grid + g2p + stress; }
};

void timed_step(MpmSolver& solver, MaterialPoints& pts, const BoundaryConditions& bc, double dt,
                PassTimes& t) {
  auto t0 = Clock::now();
  const auto lap = [&t0](double& into) {
    const auto now = Clock::now();
    into += std::chrono::duration<double>(now - t0).count();
    t0 = now;
  };
  solver.begin_step(pts);
  lap(t.grid);
  solver.map_to_grid(pts, bc, dt);
  lap(t.p2g);
  solver.complete_nodal_sums();
  solver.update_nodes(bc, dt);
  lap(t.grid);
  solver.map_to_points(pts, bc, dt);
  lap(t.g2p);
  solver.complete_remap_sums();
  lap(t.grid);
  solver.update_stress_and_move(pts, bc, dt);
  lap(t.stress);
}

}  // namespace

int main(int argc, char** argv) {
  // Cells per axis (default 50: 1,000,000 points); a larger block checks
  // that the figures hold once the points no longer fit in the last-level cache.
  const int cells = argc > 1 ? std::atoi(argv[1]) : 50;
  const int ppc = 2, steps = 100;
  const double h = 1.0, rho = 1.0, E = 1000.0, nu = 0.3;
  // One cell of margin on every side for the points to move into.
  grid::RegularGrid grid({-1.0, -1.0, -1.0}, h, {cells + 2, cells + 2, cells + 2});
  std::vector<std::unique_ptr<Material>> mats;
  mats.push_back(
      MaterialRegistry::create("linear_elastic", {{"youngs_modulus", E}, {"poisson_ratio", nu}}));
  MpmSolver solver(grid, grid::ShapeFunctionRegistry::create("linear"), std::move(mats), {});

  MaterialPoints pts;
  const double d = h / ppc;
  const double L = cells * h;
  int64_t id = 0;
  for (int k = 0; k < cells * ppc; ++k)
    for (int j = 0; j < cells * ppc; ++j)
      for (int i = 0; i < cells * ppc; ++i) {
        MaterialPointState s;
        s.density = rho;
        const Vec3 x{(i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d};
        pts.add(id++, x, d * d * d, s, 0);
        // A standing wave in all three directions keeps every pass busy.
        pts.v.back() = {0.01 * std::sin(std::numbers::pi * x[0] / L),
                        0.01 * std::sin(std::numbers::pi * x[1] / L),
                        0.01 * std::sin(std::numbers::pi * x[2] / L)};
      }
  // The triad is measured before and after the steps and the higher taken:
  // on a shared machine one measurement can land in a slow spell, and a low
  // bandwidth would flatter the fraction.
  const double stream_before = stream_triad_bytes_per_s();
  const double dt = 0.3 * solver.stable_time_step(pts);
  const BoundaryConditions bc;
  solver.step(pts, bc, dt);  // warm-up: first touch of the grid arrays
  // On a shared machine one timing scatters by several per cent: the best
  // of two rounds of `steps` steps, as bench/dpd_morse does.
  // The step's phases are timed one by one (a clock read costs tens of
  // nanoseconds against tens of milliseconds a phase) to say which pass
  // limits the step; the round's time is their sum.
  double elapsed = 1e30;
  PassTimes best;
  for (int round = 0; round < 2; ++round) {
    PassTimes t;
    for (int n = 0; n < steps; ++n) timed_step(solver, pts, bc, dt, t);
    if (t.total() < elapsed) {
      elapsed = t.total();
      best = t;
    }
  }
  const double np = static_cast<double>(pts.size());
  const double rate = np * steps / elapsed;

  // Bytes per point and step that the passes cannot avoid: pass 1 (P2G)
  // reads x, v, mass, volume0, F and the stress; pass 2 (G2P + remap)
  // reads x, mass, groups and reads and writes v; pass 3 (gradient, stress,
  // move) reads and writes x, F, the state and the work, and reads
  // volume0, mass and the material index. The grid passes stream the 7
  // nodal sums plus 4 nodal vectors a few times; nodes are 1/8 of points.
  const double d8 = sizeof(double);
  const double state = sizeof(MaterialPointState);
  const double pass1 = 3 * d8 + 3 * d8 + d8 + d8 + 9 * d8 + 6 * d8;
  const double pass2 = 3 * d8 + d8 + 4 + 2 * 3 * d8;
  const double pass3 = 2 * (3 * d8 + 9 * d8 + state + d8) + 2 * d8 + 4;
  const double nodes = static_cast<double>(grid.node_count());
  const double grid_bytes = nodes * (2 * 7 * d8 + 6 * 3 * d8 + 2 * 7 * d8);
  const double bytes_per_step = np * (pass1 + pass2 + pass3) + grid_bytes;
  const double stream = std::max(stream_before, stream_triad_bytes_per_s());
  const double fraction = bytes_per_step * steps / elapsed / stream;

  std::printf(
      "# %zu points, %d steps in %.3f s (best of 2 rounds); %.0f bytes per point-step; STREAM "
      "triad %.2f GB/s\n",
      pts.size(), steps, elapsed, bytes_per_step / np, stream / 1e9);
  const auto width = MpmSolver::simd_width();
  std::printf("# grid step built for %s: %d points per SIMD pass\n", width.isa, width.lanes);
  // Final-state checksums (not timed): compare before/after a change to
  // check that the physics stayed within round-off.
  {
    double sx = 0, sv = 0, ss = 0, sf = 0, sw = 0;
    for (size_t p = 0; p < pts.size(); ++p) {
      for (size_t a = 0; a < 3; ++a) {
        sx += pts.x[p][a] * (1.0 + 1e-3 * static_cast<double>(p % 7));
        sv += pts.v[p][a] * (1.0 + 1e-3 * static_cast<double>(p % 5));
      }
      for (int c = 0; c < 6; ++c) ss += std::abs(pts.state[p].stress[c]);
      sf += pts.F[p].determinant();
      sw += pts.work[p];
    }
    const EnergySummary e = solver.energy(pts);
    std::printf("# checksum x %.15e v %.15e |stress| %.15e sum J %.15e work %.15e\n", sx, sv, ss,
                sf, sw);
    std::printf("# energy kinetic %.15e stored %.15e work %.15e\n", e.kinetic, e.stored, e.work);
  }
  // Per pass: nanoseconds a point-step and the pass's own fraction of the
  // roofline (its bytes above over its time). A pass near 1 is limited by
  // memory; one far below it by its instructions.
  const double per_point = 1e9 / (np * steps);
  const auto pass = [&](const char* name, double seconds, double bytes) {
    std::printf("# pass %-7s %6.2f ns/point-step  %5.1f %% of the step  roofline fraction %.3f\n",
                name, seconds * per_point, 100.0 * seconds / elapsed,
                bytes * np * steps / seconds / stream);
  };
  pass("p2g", best.p2g, pass1);
  pass("g2p", best.g2p, pass2);
  pass("stress", best.stress, pass3);
  pass("grid", best.grid, grid_bytes / np);
  std::printf("BENCH mpm_particle_steps_per_s %.4g 1/s\n", rate);
  std::printf("BENCH mpm_roofline_fraction %.3f 1\n", fraction);
  return 0;
}
