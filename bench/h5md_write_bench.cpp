// The time to write one H5MD frame of a DPD run's particles (position,
// velocity, force, internal energy; 100,000 particles) on this job's ranks,
// two ways:
//  - gathered: every rank's rows gathered on rank 0 and sorted by id
//    (mpi::sorted_rows), rank 0 writing alone, as dpd_run and mpm_output
//    did before;
//  - collective: H5mdWriter on all ranks, each passing the particles it
//    holds (they reach the ranks whose row blocks hold them, and every rank
//    writes its block).
// Two layouts of the particles over the ranks: "slab", a lattice with ids
// x fastest cut across x (runs of consecutive ids, as a domain
// decomposition leaves them), and "scrambled", each particle on a random
// rank in a random order.
// Rank 0 prints BENCH lines: the median of the frames, in ms.
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "pbms/io/h5md_writer.hpp"
#include "pbms/mpi/sorted_rows.hpp"

using namespace pbms;

namespace {

constexpr int kNx = 50, kNy = 50, kNz = 40;  // 100,000 particles
constexpr int kFrames = 9;
constexpr std::size_t kWidth = 12;  // id, type, x, v, f, u

struct Local {
  std::vector<std::int64_t> ids;
  std::vector<int> species;
  std::vector<double> x, v, f, u;
};

Local particles(int rank, int ranks, bool scrambled) {
  Local p;
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> pick(0, ranks - 1);
  for (int k = 0; k < kNz; ++k) {
    for (int j = 0; j < kNy; ++j) {
      for (int i = 0; i < kNx; ++i) {
        const int owner = scrambled ? pick(rng) : i * ranks / kNx;
        if (owner != rank) continue;
        const std::int64_t id = i + kNx * (j + static_cast<std::int64_t>(kNy) * k);
        p.ids.push_back(id);
        p.species.push_back(0);
        for (const double c : {1.0 * i, 1.0 * j, 1.0 * k}) {
          p.x.push_back(3.6 * c + 0.01);
          p.v.push_back(0.1 * c);
          p.f.push_back(-0.2 * c);
        }
        p.u.push_back(0.5);
      }
    }
  }
  if (scrambled) {
    std::vector<std::size_t> order(p.ids.size());
    for (std::size_t n = 0; n < order.size(); ++n) order[n] = n;
    std::shuffle(order.begin(), order.end(), std::mt19937(rank + 3u));
    Local s;
    for (const std::size_t n : order) {
      s.ids.push_back(p.ids[n]);
      s.species.push_back(p.species[n]);
      s.x.insert(s.x.end(), p.x.begin() + 3 * n, p.x.begin() + 3 * n + 3);
      s.v.insert(s.v.end(), p.v.begin() + 3 * n, p.v.begin() + 3 * n + 3);
      s.f.insert(s.f.end(), p.f.begin() + 3 * n, p.f.begin() + 3 * n + 3);
      s.u.push_back(p.u[n]);
    }
    p = std::move(s);
  }
  return p;
}

H5mdWriter::Options options(const std::string& path) {
  H5mdWriter::Options o;
  o.path = path;
  o.velocities = o.forces = o.internal_energy = true;
  return o;
}

// One frame the old way: rows gathered and sorted on rank 0, written there.
void write_gathered(MPI_Comm comm, int rank, const Local& p, std::unique_ptr<H5mdWriter>& w,
                    const std::string& path, int frame) {
  std::vector<double> rows;
  rows.reserve(p.ids.size() * kWidth);
  for (std::size_t n = 0; n < p.ids.size(); ++n) {
    rows.insert(rows.end(), {static_cast<double>(p.ids[n]), 0.0});
    rows.insert(rows.end(), p.x.begin() + 3 * n, p.x.begin() + 3 * n + 3);
    rows.insert(rows.end(), p.v.begin() + 3 * n, p.v.begin() + 3 * n + 3);
    rows.insert(rows.end(), p.f.begin() + 3 * n, p.f.begin() + 3 * n + 3);
    rows.push_back(p.u[n]);
  }
  const auto all = mpi::sorted_rows(comm, rows, kWidth, mpi::RowsTo::kRankZero);
  if (rank != 0) return;
  const std::size_t n = all.size() / kWidth;
  std::vector<std::int64_t> ids(n);
  for (std::size_t r = 0; r < n; ++r) ids[r] = static_cast<std::int64_t>(all[r * kWidth]);
  if (!w) w = std::make_unique<H5mdWriter>(MPI_COMM_SELF, options(path), ids, std::vector<int>(n));
  std::vector<double> x, v, f, u;
  for (std::size_t r = 0; r < n; ++r) {
    const double* row = &all[r * kWidth];
    x.insert(x.end(), row + 2, row + 5);
    v.insert(v.end(), row + 5, row + 8);
    f.insert(f.end(), row + 8, row + 11);
    u.push_back(row[11]);
  }
  w->write_frame(frame, 0.001 * frame, {180, 180, 144}, ids, x, v, f, u);
}

double median(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// The median over frames of the slowest rank's time, ms.
template <class Frame>
double time_frames(MPI_Comm comm, Frame frame) {
  std::vector<double> times;
  for (int n = 0; n < kFrames; ++n) {
    MPI_Barrier(comm);
    const double t0 = MPI_Wtime();
    frame(n);
    double t = MPI_Wtime() - t0;
    MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPI_DOUBLE, MPI_MAX, comm);
    times.push_back(1e3 * t);
  }
  return median(times);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int pid = static_cast<int>(getpid());
  MPI_Bcast(&pid, 1, MPI_INT, 0, MPI_COMM_WORLD);
  const auto dir =
      std::filesystem::temp_directory_path() / ("pbms_h5md_bench_" + std::to_string(pid));
  if (rank == 0) std::filesystem::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  for (const bool scrambled : {false, true}) {
    const Local p = particles(rank, ranks, scrambled);
    const char* layout = scrambled ? "scrambled" : "slab";
    {
      std::unique_ptr<H5mdWriter> w;
      const std::string path = (dir / "gathered.h5md").string();
      const double ms = time_frames(
          MPI_COMM_WORLD, [&](int n) { write_gathered(MPI_COMM_WORLD, rank, p, w, path, n); });
      if (rank == 0)
        std::printf("BENCH h5md_frame_gathered_%s_%dranks %.2f ms\n", layout, ranks, ms);
    }
    {
      std::unique_ptr<H5mdWriter> w;
      const std::string path = (dir / "collective.h5md").string();
      const double ms = time_frames(MPI_COMM_WORLD, [&](int n) {
        if (!w) w = std::make_unique<H5mdWriter>(MPI_COMM_WORLD, options(path), p.ids, p.species);
        w->write_frame(n, 0.001 * n, {180, 180, 144}, p.ids, p.x, p.v, p.f, p.u);
      });
      if (rank == 0) {
        std::printf("BENCH h5md_frame_collective_%s_%dranks %.2f ms\n", layout, ranks, ms);
      }
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) std::filesystem::remove_all(dir);
  MPI_Finalize();
  return 0;
}
