// The cost of splitting a concurrent DPD/MPM body across two programs
// (bench/concurrent_impact.sh): the seed's concurrent-impact target (30 x
// 10 x 10 a_cg of copper, periodic across, h = 4.017 Å), its lower half
// DPD through the grid and its upper half elastic MPM, advanced for the
// same steps
//   - split: dpd_driver's and mpm_driver's parts on one rank each (world
//     ranks 0 and 1, one core each), exchanging rank to rank;
//   - monolithic: both parts in one process (InProcessLink), on rank 0;
//   - all DPD: the same bar all DPD particles through the grid, on rank 0.
// coupling_overhead_fraction counts the work of the split run, the two
// ranks' stepping time less the time each waited for the other (load
// imbalance between the parts, not a cost of the coupling), against the
// monolithic run's: (t_dpd + t_mpm - waits - t_mono) / t_mono.
// All three move at the midpoint (grid.move's default); the monolithic run
// is timed again with the step-start move, and midpoint_move_cost_ratio is
// the midpoint's time over it.
#include <mpi.h>

#include <chrono>
#include <cstdio>

#include "concurrent_bar.hpp"
#include "pbms/coupling/coupling_scheme.hpp"
#include "pbms/coupling/cross_program_link.hpp"
#include "pbms/coupling/in_process_link.hpp"

using namespace pbms;
using namespace pbms::testing;

namespace {

constexpr int kSteps = 100;
const ConcurrentBar kBar{30, 10, 18, false, false, grid::PointMove::kMidpoint};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One part per program; returns this rank's stepping time and its waits.
std::pair<double, double> split(MPI_Comm local, MPI_Comm inter, int program) {
  const double reach = dpd::cu_cg_morse_parameters().cutoff + kSkin;
  const grid::GridPartition theirs(kBar.grid(), kPeriodic, 1);
  DpdPart d;
  MpmPart m;
  std::unique_ptr<coupling::CrossProgramLink> link;
  coupling::GridSide* side = nullptr;
  if (program == 0) {
    d = dpd_part(local, kBar);
    link = std::make_unique<coupling::CrossProgramLink>(inter, *d.side, d.grid->partition(), theirs,
                                                        kBar.band(), reach);
    side = d.side.get();
  } else {
    m = mpm_part(local, kBar);
    link = std::make_unique<coupling::CrossProgramLink>(inter, *m.side, m.engine->partition(),
                                                        theirs, kBar.band(), reach);
    side = m.side.get();
  }
  coupling::CouplingScheme scheme({side}, *link, coupling::InterfaceTreatment::kMomentumConserving,
                                  coupling::GridFields::kShared, kBar.move);
  scheme.step();  // lists and buffers settle
  const double waited0 =
      link->nodal_profile().seconds_waiting + link->partner_profile().seconds_waiting;
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < kSteps; ++n) scheme.step();
  const double t = seconds_since(t0);
  const double waited =
      link->nodal_profile().seconds_waiting + link->partner_profile().seconds_waiting - waited0;
  return {t, waited};
}

double monolithic(grid::PointMove move) {
  ConcurrentBar bar = kBar;
  bar.move = move;
  DpdPart d = dpd_part(MPI_COMM_SELF, bar);
  MpmPart m = mpm_part(MPI_COMM_SELF, bar);
  coupling::InProcessLink link(*d.side, *m.side);
  coupling::CouplingScheme scheme({d.side.get(), m.side.get()}, link,
                                  coupling::InterfaceTreatment::kMomentumConserving,
                                  coupling::GridFields::kShared, move);
  scheme.step();
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < kSteps; ++n) scheme.step();
  return seconds_since(t0);
}

double all_dpd() {
  ConcurrentBar bar = kBar;
  bar.all_dpd = true;
  DpdPart d = dpd_part(MPI_COMM_SELF, bar);
  d.grid->step();
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < kSteps; ++n) d.grid->step();
  return seconds_since(t0);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size != 2) {
    if (rank == 0) std::fprintf(stderr, "concurrent_impact_bench: run on 2 ranks\n");
    MPI_Finalize();
    return 2;
  }
  MPI_Comm local = MPI_COMM_NULL, inter = MPI_COMM_NULL;
  MPI_Comm_split(MPI_COMM_WORLD, rank, rank, &local);
  MPI_Intercomm_create(local, 0, MPI_COMM_WORLD, 1 - rank, 77, &inter);
  const auto [t, waited] = split(local, inter, rank);
  double mine[2] = {t, waited}, both[4] = {};
  MPI_Gather(mine, 2, MPI_DOUBLE, both, 2, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  double t_mono = 0.0, t_dpd = 0.0, t_step_start = 0.0;
  if (rank == 0) {
    t_mono = monolithic(kBar.move);
    t_dpd = all_dpd();
    t_step_start = monolithic(grid::PointMove::kStepStart);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    const double work = both[0] - both[1] + both[2] - both[3];
    const double wall = std::max(both[0], both[2]);
    std::printf(
        "# %d steps; split: dpd rank %.3f s (waited %.3f s), mpm rank %.3f s (waited %.3f s)\n",
        kSteps, both[0], both[1], both[2], both[3]);
    std::printf("# monolithic %.3f s (step-start move %.3f s), all DPD %.3f s, split wall %.3f s\n",
                t_mono, t_step_start, t_dpd, wall);
    std::printf("BENCH coupling_overhead_fraction %.4f 1\n", (work - t_mono) / t_mono);
    std::printf("BENCH concurrent_speedup_vs_dpd_only %.4f 1\n", t_dpd / t_mono);
    std::printf("BENCH concurrent_split_wall_speedup_vs_dpd_only %.4f 1\n", t_dpd / wall);
    std::printf("BENCH midpoint_move_cost_ratio %.4f 1\n", t_mono / t_step_start);
  }
  MPI_Comm_free(&inter);
  MPI_Comm_free(&local);
  MPI_Finalize();
  return 0;
}
