// How the cells of an MPM grid are split into one box per rank, and which
// nodes neighbouring boxes (and periodic images) share. Pure geometry: the
// MPI side (HaloSum) and the particle migration only read it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "pbms/grid/regular_grid.hpp"

namespace pbms::grid {

// Cells [lo, hi) per axis.
struct CellBox {
  std::array<int, 3> lo{};
  std::array<int, 3> hi{};
  bool operator==(const CellBox&) const = default;
};

// A block of another rank's (or this rank's periodic image's) nodes that
// coincide with nodes of this rank. `nodes` is in this rank's global node
// indices; the peer sees the same nodes shifted by -shift * cells.
struct NodeOverlap {
  int rank = 0;
  std::array<int, 3> shift{};  // -1, 0 or +1 per axis (periodic images)
  NodeBox nodes;
};

class GridPartition {
 public:
  // Splits `grid` over `ranks` boxes arranged as a process grid chosen to
  // minimise the shared-node surface; every box gets at least one cell per
  // axis (throws pbms::Error when the grid is too small for that). On a
  // periodic axis node `cells` is the image of node 0.
  GridPartition(const RegularGrid& grid, const std::array<bool, 3>& periodic, int ranks);

  [[nodiscard]] const RegularGrid& grid() const { return grid_; }
  [[nodiscard]] const std::array<bool, 3>& periodic() const { return periodic_; }
  [[nodiscard]] int ranks() const { return ranks_; }
  [[nodiscard]] const std::array<int, 3>& dims() const { return dims_; }

  [[nodiscard]] CellBox cells_of(int rank) const;
  // The nodes a rank's points touch with linear shape functions: its cells'
  // corners, shared on faces with the neighbouring boxes.
  [[nodiscard]] NodeBox nodes_of(int rank) const;
  // The nodes a rank writes in output: the lower corner of each of its
  // cells, plus the grid's upper faces. These tile the grid's nodes exactly
  // once; on a periodic axis the upper face repeats the lower one, which
  // keeps the written grid whole for viewers.
  [[nodiscard]] NodeBox owned_nodes_of(int rank) const;
  // The rank whose cells hold x (a position inside the grid, already
  // wrapped on periodic axes); the upper face belongs to the last cell.
  [[nodiscard]] int owner_of(const std::array<double, 3>& x) const;
  // Every block of nodes `rank` shares with another rank or an image of
  // itself, in a fixed order.
  [[nodiscard]] std::vector<NodeOverlap> overlaps_of(int rank) const;

 private:
  [[nodiscard]] std::array<int, 3> coords_of(int rank) const;
  [[nodiscard]] int rank_of(const std::array<int, 3>& coords) const;
  [[nodiscard]] int split(int axis, int part) const;  // first cell of a part

  RegularGrid grid_;
  std::array<bool, 3> periodic_;
  int ranks_;
  std::array<int, 3> dims_{1, 1, 1};
};

}  // namespace pbms::grid
