// GridPartition splits cells into boxes that tile the grid, and HaloSum
// completes nodal sums across boxes and periodic images.
#include <gtest/gtest.h>

#include <mpi.h>

#include <set>

#include "pbms/error.hpp"
#include "pbms/grid/grid_partition.hpp"
#include "pbms/grid/halo_sum.hpp"

using namespace pbms;
using namespace pbms::grid;

TEST(GridPartition, BoxesTileTheCellsAndOwnedNodesTileTheNodes) {
  const RegularGrid g({0, 0, 0}, 1.0, {7, 5, 3});
  for (const std::array<bool, 3> periodic :
       {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, false, true}}) {
    for (int ranks : {1, 2, 3, 4, 6, 12}) {
      const GridPartition part(g, periodic, ranks);
      EXPECT_EQ(part.dims()[0] * part.dims()[1] * part.dims()[2], ranks);
      std::vector<int> cell_owner(static_cast<size_t>(g.cell_count()), -1);
      std::multiset<std::int64_t> owned;
      for (int r = 0; r < ranks; ++r) {
        const auto c = part.cells_of(r);
        for (int k = c.lo[2]; k < c.hi[2]; ++k)
          for (int j = c.lo[1]; j < c.hi[1]; ++j)
            for (int i = c.lo[0]; i < c.hi[0]; ++i) {
              auto& o = cell_owner[static_cast<size_t>(g.cell_index({i, j, k}))];
              EXPECT_EQ(o, -1);
              o = r;
              // The owner of a cell's centre is the rank whose box holds it.
              EXPECT_EQ(part.owner_of({i + 0.5, j + 0.5, k + 0.5}), r);
            }
        const auto n = part.owned_nodes_of(r);
        for (int k = n.lo[2]; k < n.hi[2]; ++k)
          for (int j = n.lo[1]; j < n.hi[1]; ++j)
            for (int i = n.lo[0]; i < n.hi[0]; ++i) owned.insert(g.node_index({i, j, k}));
      }
      for (const int o : cell_owner) EXPECT_GE(o, 0);
      // Every node once.
      EXPECT_EQ(static_cast<std::int64_t>(owned.size()), g.node_count());
      EXPECT_EQ(std::set<std::int64_t>(owned.begin(), owned.end()).size(), owned.size());
    }
  }
}

TEST(GridPartition, OverlapsAreSymmetric) {
  const RegularGrid g({0, 0, 0}, 1.0, {6, 4, 2});
  const GridPartition part(g, {true, true, false}, 4);
  for (int r = 0; r < 4; ++r) {
    for (const auto& ov : part.overlaps_of(r)) {
      bool found = false;
      for (const auto& back : part.overlaps_of(ov.rank)) {
        if (back.rank != r) continue;
        if (back.shift != std::array<int, 3>{-ov.shift[0], -ov.shift[1], -ov.shift[2]}) continue;
        NodeBox moved = back.nodes;
        for (size_t a = 0; a < 3; ++a) {
          moved.lo[a] -= back.shift[a] * g.cells()[a];
          moved.hi[a] -= back.shift[a] * g.cells()[a];
        }
        found = found || moved == ov.nodes;
      }
      EXPECT_TRUE(found) << "rank " << r << " -> " << ov.rank;
    }
  }
}

TEST(GridPartition, TooManyRanksIsAnError) {
  const RegularGrid g({0, 0, 0}, 1.0, {2, 1, 1});
  EXPECT_THROW(GridPartition(g, {false, false, false}, 3), pbms::Error);
}

TEST(HaloSum, PeriodicImagesOfOneRankAddUp) {
  // One rank, periodic in x: node 0 and node 4 are one node, so after the
  // sum both hold the two parts together; the other nodes are untouched.
  const RegularGrid g({0, 0, 0}, 1.0, {4, 1, 1});
  const GridPartition part(g, {true, false, false}, 1);
  pbms::mpi::HaloSum halo(MPI_COMM_SELF, part);
  const NodeBox box = part.nodes_of(0);
  std::vector<double> data(static_cast<size_t>(box.count()) * 2);
  for (size_t n = 0; n < data.size() / 2; ++n) {
    data[2 * n] = static_cast<double>(n + 1);
    data[2 * n + 1] = -1.0;  // outside `components`: must not change
  }
  std::vector<double> before = data;
  halo.sum(data.data(), 1, 2);
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      const auto lo = static_cast<size_t>(box.local_index({0, j, k}));
      const auto hi = static_cast<size_t>(box.local_index({4, j, k}));
      EXPECT_DOUBLE_EQ(data[2 * lo], before[2 * lo] + before[2 * hi]);
      EXPECT_DOUBLE_EQ(data[2 * hi], before[2 * lo] + before[2 * hi]);
      for (int i = 1; i < 4; ++i) {
        const auto m = static_cast<size_t>(box.local_index({i, j, k}));
        EXPECT_DOUBLE_EQ(data[2 * m], before[2 * m]);
      }
    }
  }
  for (size_t n = 0; n < data.size() / 2; ++n) EXPECT_EQ(data[2 * n + 1], -1.0);
}

TEST(RegularGrid, WrappedMovesPointsIntoThePeriodicAxesOnly) {
  const RegularGrid g({-1, 0, 0}, 0.5, {4, 2, 2});  // x in [-1, 1), y, z in [0, 1)
  const auto w = g.wrapped({1.25, -0.25, 1.5}, {true, true, false});
  EXPECT_DOUBLE_EQ(w[0], -0.75);
  EXPECT_DOUBLE_EQ(w[1], 0.75);
  EXPECT_DOUBLE_EQ(w[2], 1.5);  // not periodic: left alone
  EXPECT_DOUBLE_EQ(g.wrapped({1.0, 0, 0}, {true, false, false})[0], -1.0);  // upper face = lower
  EXPECT_DOUBLE_EQ(g.wrapped({-5.0, 0, 0}, {true, false, false})[0], -1.0);
}
