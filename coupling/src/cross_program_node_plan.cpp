#include "pbms/coupling/cross_program_node_plan.hpp"

#include "pbms/error.hpp"

namespace pbms::coupling {
namespace {

grid::NodeBox shifted(grid::NodeBox b, const std::array<int, 3>& shift,
                      const std::array<int, 3>& cells) {
  for (size_t a = 0; a < 3; ++a) {
    b.lo[a] += shift[a] * cells[a];
    b.hi[a] += shift[a] * cells[a];
  }
  return b;
}

// The blocks a receiver (box `box`) takes from a sender's unique nodes
// `from`, over every periodic image, in a fixed order.
void blocks(const grid::NodeBox& box, const grid::NodeBox& from, int peer,
            const grid::GridPartition& p, std::vector<NodeTransfer>& out) {
  const auto& cells = p.grid().cells();
  for (int sz = -1; sz <= 1; ++sz) {
    for (int sy = -1; sy <= 1; ++sy) {
      for (int sx = -1; sx <= 1; ++sx) {
        const std::array<int, 3> s{sx, sy, sz};
        bool allowed = true;
        for (size_t a = 0; a < 3; ++a) allowed = allowed && (s[a] == 0 || p.periodic()[a]);
        if (!allowed) continue;
        const grid::NodeBox common = box.intersected(shifted(from, s, cells));
        if (!common.empty()) out.push_back({peer, s, common});
      }
    }
  }
}

void check_same_grid(const grid::GridPartition& a, const grid::GridPartition& b) {
  const auto& ga = a.grid();
  const auto& gb = b.grid();
  if (ga.cells() != gb.cells() || ga.cell_size() != gb.cell_size() || ga.origin() != gb.origin() ||
      a.periodic() != b.periodic()) {
    throw Error("nodal sum across programs: the two programs' grids differ");
  }
}

}  // namespace

grid::NodeBox unique_nodes_of(const grid::GridPartition& p, int rank) {
  grid::NodeBox b = p.owned_nodes_of(rank);
  for (size_t a = 0; a < 3; ++a) {
    if (p.periodic()[a] && b.hi[a] == p.grid().cells()[a] + 1) b.hi[a] -= 1;
  }
  return b;
}

std::vector<NodeTransfer> receives_of(const grid::GridPartition& mine, int rank,
                                      const grid::GridPartition& theirs,
                                      const grid::NodeBox& band) {
  check_same_grid(mine, theirs);
  std::vector<NodeTransfer> out;
  const grid::NodeBox box = mine.nodes_of(rank);
  for (int s = 0; s < theirs.ranks(); ++s) {
    blocks(box, unique_nodes_of(theirs, s).intersected(band), s, mine, out);
  }
  return out;
}

std::vector<NodeTransfer> sends_of(const grid::GridPartition& mine, int rank,
                                   const grid::GridPartition& theirs, const grid::NodeBox& band) {
  check_same_grid(mine, theirs);
  std::vector<NodeTransfer> out;
  const grid::NodeBox from = unique_nodes_of(mine, rank).intersected(band);
  for (int r = 0; r < theirs.ranks(); ++r) blocks(theirs.nodes_of(r), from, r, mine, out);
  return out;
}

}  // namespace pbms::coupling
