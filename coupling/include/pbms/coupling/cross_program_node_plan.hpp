// Which grid nodes go between which ranks of two programs that share one
// grid, each split over its own ranks by its own GridPartition. Pure
// geometry: NodalSumAcrossPrograms does the MPI.
//
// Each program has completed its own nodal sums first (HaloSum), so every
// copy of a node in a program holds that program's whole part. A rank
// therefore takes each node it holds from exactly one rank of the other
// program: the one whose cells have it as a lower corner (its unique
// nodes). A periodic image is the same node: node `cells` of a periodic
// axis comes from the owner of node 0.
#pragma once

#include <array>
#include <vector>

#include "pbms/grid/grid_partition.hpp"

namespace pbms::coupling {

// One block of nodes between a rank and a rank of the other program.
// `nodes` is in the receiver's node indices; the sender reads them at
// nodes - shift * cells (its own indices).
struct NodeTransfer {
  int peer = 0;  // rank in the other program
  std::array<int, 3> shift{};
  grid::NodeBox nodes;
};

// Each node of the grid once: a rank's lower cell corners, plus the upper
// faces of non-periodic axes.
[[nodiscard]] grid::NodeBox unique_nodes_of(const grid::GridPartition& p, int rank);

// What rank `rank` of the program split by `mine` receives from the ranks
// of the program split by `theirs`: every node of its box inside `band`
// (global indices, before wrapping), each once. Both partitions must be of
// the same grid and periodic axes.
[[nodiscard]] std::vector<NodeTransfer> receives_of(const grid::GridPartition& mine, int rank,
                                                    const grid::GridPartition& theirs,
                                                    const grid::NodeBox& band);

// What rank `rank` of `mine` sends: the same blocks as the receivers
// compute for it (NodeTransfer::peer is the receiver).
[[nodiscard]] std::vector<NodeTransfer> sends_of(const grid::GridPartition& mine, int rank,
                                                 const grid::GridPartition& theirs,
                                                 const grid::NodeBox& band);

}  // namespace pbms::coupling
