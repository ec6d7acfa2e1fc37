// The cost of the exchanges across programs on this machine's MPI, for the
// scaling model of docs/concurrent.md. The job's ranks split into two
// programs (the first half and the rest) joined by an intercommunicator:
//  - ping-pong between the two programs' first ranks: 8-byte and 1-MiB
//    messages give the latency alpha and bandwidth beta of t(n) = alpha +
//    n / beta;
//  - NodalSumAcrossPrograms on the concurrent-impact grid (a 120 x 12 x 12
//    cell rod of 4 Å cells, periodic across, interface at mid-length, a band
//    of four cells), 7 then 3 components as one step does;
//  - PointGhostsAcrossPrograms: the MPM half's points (one per cell corner
//    region, 8 per cell) within 11 Å of the DPD half.
// Rank 0 prints BENCH lines.
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "pbms/coupling/nodal_sum_across_programs.hpp"
#include "pbms/coupling/point_ghosts_across_programs.hpp"

using namespace pbms;
using namespace pbms::coupling;

namespace {

struct Job {
  int world_rank = 0, world_size = 1, program = 0, rank = 0, ranks[2] = {1, 1};
  MPI_Comm local = MPI_COMM_NULL, inter = MPI_COMM_NULL;
};

Job split() {
  Job j;
  MPI_Comm_rank(MPI_COMM_WORLD, &j.world_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &j.world_size);
  const int first = j.world_size / 2;
  j.program = j.world_rank < first ? 0 : 1;
  j.ranks[0] = first;
  j.ranks[1] = j.world_size - first;
  MPI_Comm_split(MPI_COMM_WORLD, j.program, j.world_rank, &j.local);
  MPI_Intercomm_create(j.local, 0, MPI_COMM_WORLD, j.program == 0 ? first : 0, 5, &j.inter);
  MPI_Comm_rank(j.local, &j.rank);
  return j;
}

// Seconds for one one-way message of `bytes` (half a round trip, best of
// several rounds), measured between the programs' first ranks.
double one_way(const Job& j, int bytes) {
  std::vector<char> buf(static_cast<size_t>(bytes));
  double best = 1e30;
  for (int round = 0; round < 5; ++round) {
    const int reps = bytes > 4096 ? 20 : 2000;
    MPI_Barrier(MPI_COMM_WORLD);
    const double t0 = MPI_Wtime();
    for (int r = 0; r < reps && j.rank == 0; ++r) {
      if (j.program == 0) {
        MPI_Send(buf.data(), bytes, MPI_CHAR, 0, 1, j.inter);
        MPI_Recv(buf.data(), bytes, MPI_CHAR, 0, 1, j.inter, MPI_STATUS_IGNORE);
      } else {
        MPI_Recv(buf.data(), bytes, MPI_CHAR, 0, 1, j.inter, MPI_STATUS_IGNORE);
        MPI_Send(buf.data(), bytes, MPI_CHAR, 0, 1, j.inter);
      }
    }
    best = std::min(best, (MPI_Wtime() - t0) / (2.0 * reps));
  }
  MPI_Bcast(&best, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  Job j = split();
  const double t_small = one_way(j, 8), t_big = one_way(j, 1 << 20);
  const double alpha = t_small;
  const double beta = (1 << 20) / (t_big - t_small);

  const double h = 4.0;
  const grid::RegularGrid g({0, 0, 0}, h, {120, 12, 12});
  const std::array<bool, 3> periodic{false, true, true};
  const grid::GridPartition mine(g, periodic, j.ranks[j.program]);
  const grid::GridPartition theirs(g, periodic, j.ranks[1 - j.program]);
  const grid::NodeBox band{{58, 0, 0}, {63, 13, 13}};
  NodalSumAcrossPrograms sum(j.inter, mine, theirs, band);
  const grid::NodeBox box = mine.nodes_of(j.rank);
  std::vector<double> data(static_cast<size_t>(box.count()) * 8, 1.0);
  const int steps = 2000;
  MPI_Barrier(MPI_COMM_WORLD);
  double t0 = MPI_Wtime();
  for (int s = 0; s < steps; ++s) {
    sum.sum(data.data(), 7, 8);
    sum.sum(data.data() + 1, 3, 8);
  }
  double per_step = (MPI_Wtime() - t0) / steps;
  MPI_Allreduce(MPI_IN_PLACE, &per_step, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  long long bytes[2] = {sum.profile().bytes_sent / (2 * steps) * 2,
                        sum.profile().messages_sent / steps};
  MPI_Allreduce(MPI_IN_PLACE, bytes, 2, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);

  // Ghosts: program 0 is the MPM side (x >= 240 Å), program 1 the DPD
  // side (its slabs of x < 240 Å). Points 2 per cell edge in the MPM half.
  PeriodicLengths lengths;
  lengths.length = {0.0, 48.0, 48.0};
  const double reach = 11.0;
  double ghost_step = 0.0;
  long long ghost_bytes = 0;
  if (j.program == 0) {
    const auto c = mine.cells_of(j.rank);
    SpaceBox b{{c.lo[0] * h, c.lo[1] * h, c.lo[2] * h}, {c.hi[0] * h, c.hi[1] * h, c.hi[2] * h}};
    std::vector<std::int64_t> id;
    std::vector<Vec3> x, v;
    std::vector<double> m;
    for (int k = 2 * c.lo[2]; k < 2 * c.hi[2]; ++k)
      for (int jj = 2 * c.lo[1]; jj < 2 * c.hi[1]; ++jj)
        for (int i = std::max(2 * c.lo[0], 120); i < 2 * c.hi[0]; ++i) {
          id.push_back(static_cast<std::int64_t>(id.size()));
          x.push_back({(i + 0.5) * h / 2, (jj + 0.5) * h / 2, (k + 0.5) * h / 2});
          v.push_back({0.0, 0.0, 0.0});
          m.push_back(508.37);
        }
    PointGhostsAcrossPrograms ghosts(j.inter, PointGhostsAcrossPrograms::Side::kSender, b, reach,
                                     lengths);
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = MPI_Wtime();
    for (int s = 0; s < steps; ++s) ghosts.send(id, x, v, m);
    ghost_step = (MPI_Wtime() - t0) / steps;
    ghost_bytes = ghosts.profile().bytes_sent / steps;
  } else {
    const double lx = 240.0 / j.ranks[1];
    SpaceBox b{{j.rank * lx, 0.0, 0.0}, {(j.rank + 1) * lx, 48.0, 48.0}};
    PointGhostsAcrossPrograms ghosts(j.inter, PointGhostsAcrossPrograms::Side::kReceiver, b, reach,
                                     lengths);
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = MPI_Wtime();
    for (int s = 0; s < steps; ++s) (void)ghosts.receive();
    ghost_step = (MPI_Wtime() - t0) / steps;
  }
  MPI_Allreduce(MPI_IN_PLACE, &ghost_step, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &ghost_bytes, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);

  if (j.world_rank == 0) {
    std::printf("BENCH coupling_latency %.3g us\n", alpha * 1e6);
    std::printf("BENCH coupling_bandwidth %.3g GB/s\n", beta * 1e-9);
    std::printf("BENCH nodal_sum_per_step %.3g us\n", per_step * 1e6);
    std::printf("BENCH nodal_sum_bytes_per_step %lld B\n", bytes[0]);
    std::printf("BENCH nodal_sum_messages_per_step %lld 1\n", bytes[1]);
    std::printf("BENCH ghost_exchange_per_step %.3g us\n", ghost_step * 1e6);
    std::printf("BENCH ghost_bytes_per_step %lld B\n", ghost_bytes);
  }
  MPI_Comm_free(&j.inter);
  MPI_Comm_free(&j.local);
  MPI_Finalize();
  return 0;
}
