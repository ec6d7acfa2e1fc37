// CheckpointArchive written in parallel HDF5 by the 3 ranks of this job:
// each rank puts rows of its own (rank 1 none, as a rank whose domain is
// empty), rank 0 the arrays and bytes for the whole program. Read back, every rank
// holds rank 0's arrays and all rows rank after rank, bit for bit, with how
// many rows each rank wrote; rows written by one rank read back the same.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/mpi/comm.hpp"

using pbms::CheckpointArchive;

namespace {

constexpr std::size_t kWidth = 4;
const std::string kIdentity = "stage 'pull' (dpd_run), parameters 0000000000000001; PBMS test";

// Rank r's rows: 5 + 3r of them (none on rank 1), values that no other
// rank's rows share and that round-trip only when written as bits.
std::vector<double> rows_of(int rank) {
  if (rank == 1) return {};
  std::vector<double> v;
  for (std::size_t k = 0; k < (5 + 3 * static_cast<std::size_t>(rank)) * kWidth; ++k) {
    v.push_back(rank * 1000.0 + static_cast<double>(k) + 1.0 / 3.0);
  }
  return v;
}

std::filesystem::path shared_file(MPI_Comm comm, const std::string& name) {
  int pid = ::getpid();
  MPI_Bcast(&pid, 1, MPI_INT, 0, comm);
  return std::filesystem::temp_directory_path() / ("pbms_ckpt_ranks_" + std::to_string(pid)) / name;
}

}  // namespace

TEST(CheckpointArchiveRanks, EveryRankWritesItsRowsAtItsPlace) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const auto file = shared_file(MPI_COMM_WORLD, "step_000000000100.h5");

  CheckpointArchive a;
  a.put_rows("engine/particles", rows_of(rank), kWidth);
  // Only rank 0's whole-program arrays are written: the others' differ.
  a.put("engine/step", rank == 0 ? 100.0 : -1.0);
  a.put("probes/series", rank == 0 ? std::vector<double>{0.5, 0.25} : std::vector<double>{});
  a.put_bytes("lammps/restart", rank == 0 ? std::string("restart\0file", 12) : "other");
  a.write(file, kIdentity, MPI_COMM_WORLD);
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_TRUE(std::filesystem::exists(file));
  EXPECT_FALSE(std::filesystem::exists(file.string() + ".partial"));

  const CheckpointArchive b = CheckpointArchive::read(file, kIdentity, MPI_COMM_WORLD);
  std::vector<double> all, counts;
  for (int r = 0; r < ranks; ++r) {
    const auto mine = rows_of(r);
    all.insert(all.end(), mine.begin(), mine.end());
    counts.push_back(static_cast<double>(mine.size() / kWidth));
  }
  EXPECT_EQ(b.get("engine/particles"), all);
  EXPECT_EQ(b.rank_counts("engine/particles"), counts);
  EXPECT_EQ(b.scalar("engine/step"), 100.0);
  EXPECT_EQ(b.get("probes/series"), (std::vector<double>{0.5, 0.25}));
  EXPECT_EQ(b.bytes("lammps/restart"), std::string("restart\0file", 12));

  // The same rows from one process: the same file contents.
  const auto single = shared_file(MPI_COMM_WORLD, "single.h5");
  if (rank == 0) {
    CheckpointArchive c;
    c.put_rows("engine/particles", all, kWidth);
    c.write(single, kIdentity);
    const CheckpointArchive d = CheckpointArchive::read(single, kIdentity, MPI_COMM_SELF);
    EXPECT_EQ(d.get("engine/particles"), all);
    EXPECT_EQ(d.rank_counts("engine/particles"),
              std::vector<double>{static_cast<double>(all.size() / kWidth)});
    std::filesystem::remove_all(file.parent_path());
  }
  MPI_Barrier(MPI_COMM_WORLD);
}
