// Which nodes go between the ranks of two programs on one grid: every node
// a rank holds inside the band comes from exactly one rank of the other
// program, and what each sender sends is what its receiver expects.
#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "pbms/coupling/cross_program_node_plan.hpp"

using namespace pbms;
using namespace pbms::coupling;

namespace {

struct Case {
  int ranks_a, ranks_b;
  std::array<bool, 3> periodic;
};

// Canonical index of a node: periodic images folded onto [0, cells).
std::array<int, 3> canonical(std::array<int, 3> ijk, const grid::GridPartition& p) {
  for (size_t a = 0; a < 3; ++a) {
    const int n = p.grid().cells()[a];
    if (p.periodic()[a]) ijk[a] = ((ijk[a] % n) + n) % n;
  }
  return ijk;
}

}  // namespace

TEST(CrossProgramNodePlan, EveryNodeInTheBandComesOnceFromItsOwner) {
  const grid::RegularGrid g({0, 0, 0}, 2.0, {9, 6, 5});
  const grid::NodeBox band{{3, 0, 0}, {7, 7, 6}};
  for (const Case c : {Case{1, 1, {false, false, false}}, Case{2, 2, {true, false, false}},
                       Case{1, 3, {true, true, true}}, Case{3, 4, {false, true, true}}}) {
    const grid::GridPartition a(g, c.periodic, c.ranks_a), b(g, c.periodic, c.ranks_b);
    for (int r = 0; r < a.ranks(); ++r) {
      std::map<std::array<int, 3>, int> times;
      for (const auto& t : receives_of(a, r, b, band)) {
        EXPECT_TRUE(a.nodes_of(r).intersected(t.nodes) == t.nodes);
        for (int k = t.nodes.lo[2]; k < t.nodes.hi[2]; ++k)
          for (int j = t.nodes.lo[1]; j < t.nodes.hi[1]; ++j)
            for (int i = t.nodes.lo[0]; i < t.nodes.hi[0]; ++i) {
              const std::array<int, 3> ijk{i, j, k};
              ++times[ijk];
              // The sender owns the node's canonical image.
              std::array<int, 3> at{i, j, k};
              for (size_t x = 0; x < 3; ++x) at[x] -= t.shift[x] * g.cells()[x];
              EXPECT_TRUE(unique_nodes_of(b, t.peer).contains(at));
              EXPECT_EQ(canonical(at, b), at);
            }
      }
      const auto box = a.nodes_of(r);
      for (int k = box.lo[2]; k < box.hi[2]; ++k)
        for (int j = box.lo[1]; j < box.hi[1]; ++j)
          for (int i = box.lo[0]; i < box.hi[0]; ++i) {
            const auto can = canonical({i, j, k}, a);
            const int expect = band.contains(can) ? 1 : 0;
            const std::array<int, 3> ijk{i, j, k};
            EXPECT_EQ(times[ijk], expect) << i << " " << j << " " << k;
          }
    }
    // Sends of b's rank s to a's rank r are exactly r's receives from s.
    using Key = std::tuple<int, int, std::array<int, 3>>;
    std::map<Key, grid::NodeBox> sent, expected;
    for (int s = 0; s < b.ranks(); ++s)
      for (const auto& t : sends_of(b, s, a, band)) sent[{s, t.peer, t.shift}] = t.nodes;
    for (int r = 0; r < a.ranks(); ++r)
      for (const auto& t : receives_of(a, r, b, band)) expected[{t.peer, r, t.shift}] = t.nodes;
    EXPECT_EQ(sent, expected);
  }
}

TEST(CrossProgramNodePlan, RefusesDifferentGrids) {
  const grid::GridPartition a(grid::RegularGrid({0, 0, 0}, 2.0, {4, 4, 4}), {}, 1);
  const grid::GridPartition b(grid::RegularGrid({0, 0, 0}, 2.0, {4, 4, 5}), {}, 1);
  EXPECT_ANY_THROW((void)receives_of(a, 0, b, a.grid().node_box()));
}
