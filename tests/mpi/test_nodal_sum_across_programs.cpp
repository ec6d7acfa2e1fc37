// NodalSumAcrossPrograms between two groups of this job's ranks, each
// playing one program with its own split of one grid: after the sum every
// copy of every node in the band holds both programs' parts, exactly, and
// the nodes outside it keep their own. Started by mpirun on 2 and 4 ranks
// (1+1; 1+3, 2+2, 3+1).
#include <gtest/gtest.h>
#include <mpi.h>

#include "pbms/coupling/nodal_sum_across_programs.hpp"
#include "two_programs.hpp"

using namespace pbms;
using namespace pbms::coupling;

namespace {

// A program's part at node ijk (canonical), component c: exact in binary.
double part(int program, const std::array<int, 3>& ijk, int c) {
  const double base = 1.0 + ijk[0] + 16.0 * ijk[1] + 256.0 * ijk[2] + 4096.0 * c;
  return program == 0 ? base : 0.5 * base + 7.0;
}

std::array<int, 3> canonical(std::array<int, 3> ijk, const grid::RegularGrid& g,
                             const std::array<bool, 3>& periodic) {
  for (size_t a = 0; a < 3; ++a) {
    const int n = g.cells()[a];
    if (periodic[a]) ijk[a] = ((ijk[a] % n) + n) % n;
  }
  return ijk;
}

void check_split(int first_program_ranks, const std::array<bool, 3>& periodic,
                 const grid::RegularGrid& g = grid::RegularGrid({-3.0, 0.0, 1.0}, 1.5, {8, 5, 6}),
                 const grid::NodeBox& band = grid::NodeBox{{2, 0, 0}, {6, 6, 7}}) {
  const TwoPrograms job(first_program_ranks);
  const int program = job.program, rank = job.rank;
  const int* ranks = job.ranks;

  const grid::GridPartition mine(g, periodic, ranks[program]);
  const grid::GridPartition theirs(g, periodic, ranks[1 - program]);
  NodalSumAcrossPrograms sum(job.inter, mine, theirs, band);

  constexpr int kComponents = 7, kStride = 8;
  const grid::NodeBox box = mine.nodes_of(rank);
  std::vector<double> data(static_cast<size_t>(box.count()) * kStride, -1.0);
  const auto at = [&](const std::array<int, 3>& ijk, int c) -> double& {
    return data[static_cast<size_t>(box.local_index(ijk)) * kStride + static_cast<size_t>(c)];
  };
  for (int k = box.lo[2]; k < box.hi[2]; ++k)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int i = box.lo[0]; i < box.hi[0]; ++i)
        for (int c = 0; c < kComponents; ++c)
          at({i, j, k}, c) = part(program, canonical({i, j, k}, g, periodic), c);

  sum.sum(data.data(), kComponents, kStride);

  int wrong = 0;
  for (int k = box.lo[2]; k < box.hi[2]; ++k)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int i = box.lo[0]; i < box.hi[0]; ++i) {
        const auto can = canonical({i, j, k}, g, periodic);
        for (int c = 0; c < kComponents; ++c) {
          const double expect =
              band.contains(can) ? part(0, can, c) + part(1, can, c) : part(program, can, c);
          wrong += at({i, j, k}, c) != expect ? 1 : 0;
        }
        wrong += at({i, j, k}, kComponents) != -1.0 ? 1 : 0;  // lanes past `components`
      }
  EXPECT_EQ(wrong, 0) << "program " << program << " rank " << rank << " of split "
                      << first_program_ranks << "+" << ranks[1];
  EXPECT_EQ(sum.profile().exchanges, 1);
}

}  // namespace

TEST(NodalSumAcrossPrograms, EveryCopyHoldsBothProgramsPartsExactly) {
  for (int first = 1; first < world_size(); ++first) {
    for (const auto periodic :
         {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, false, true},
          std::array<bool, 3>{true, true, true}}) {
      check_split(first, periodic);
    }
  }
}

// A concurrent bar's grid: free along x, periodic across, the band a few
// node planes either side of the interface (tests/mpi/test_concurrent_split.cpp).
TEST(NodalSumAcrossPrograms, ABarPeriodicAcrossWithABandAroundItsInterface) {
  const grid::RegularGrid g({-14.46, 0.0, 0.0}, 3.615, {24, 8, 8});
  for (int first = 1; first < world_size(); ++first) {
    check_split(first, {false, true, true}, g, {{9, 0, 0}, {16, 9, 9}});
  }
}
