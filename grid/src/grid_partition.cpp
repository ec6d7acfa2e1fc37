#include "pbms/grid/grid_partition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::grid {

GridPartition::GridPartition(const RegularGrid& grid, const std::array<bool, 3>& periodic,
                             int ranks)
    : grid_(grid), periodic_(periodic), ranks_(ranks) {
  if (ranks < 1) throw Error("grid partition: the rank count must be at least 1");
  const auto& c = grid.cells();
  // Brute force over factorisations: rank counts are small, and the cost of
  // a box is the nodes it shares, i.e. its surface in cells.
  double best = std::numeric_limits<double>::infinity();
  for (int px = 1; px <= ranks; ++px) {
    if (ranks % px != 0) continue;
    for (int py = 1; py <= ranks / px; ++py) {
      if ((ranks / px) % py != 0) continue;
      const int pz = ranks / px / py;
      if (px > c[0] || py > c[1] || pz > c[2]) continue;
      const double bx = double(c[0]) / px, by = double(c[1]) / py, bz = double(c[2]) / pz;
      const double surface = bx * by + by * bz + bx * bz;
      if (surface < best - 1e-12) {
        best = surface;
        dims_ = {px, py, pz};
      }
    }
  }
  if (!std::isfinite(best)) {
    throw Error(fmt::format(
        "the MPM grid of {}x{}x{} cells cannot be split over {} ranks with at least one cell "
        "per rank and axis; use fewer ranks or a larger grid",
        c[0], c[1], c[2], ranks));
  }
}

int GridPartition::split(int axis, int part) const {
  const auto a = static_cast<size_t>(axis);
  return static_cast<int>(int64_t{grid_.cells()[a]} * part / dims_[a]);
}

std::array<int, 3> GridPartition::coords_of(int rank) const {
  return {rank % dims_[0], (rank / dims_[0]) % dims_[1], rank / (dims_[0] * dims_[1])};
}

int GridPartition::rank_of(const std::array<int, 3>& p) const {
  return p[0] + dims_[0] * (p[1] + dims_[1] * p[2]);
}

CellBox GridPartition::cells_of(int rank) const {
  const auto p = coords_of(rank);
  CellBox b;
  for (int a = 0; a < 3; ++a) {
    const auto aa = static_cast<size_t>(a);
    b.lo[aa] = split(a, p[aa]);
    b.hi[aa] = split(a, p[aa] + 1);
  }
  return b;
}

NodeBox GridPartition::nodes_of(int rank) const {
  const auto c = cells_of(rank);
  return {c.lo, {c.hi[0] + 1, c.hi[1] + 1, c.hi[2] + 1}};
}

NodeBox GridPartition::owned_nodes_of(int rank) const {
  const auto c = cells_of(rank);
  NodeBox b{c.lo, c.hi};
  for (size_t a = 0; a < 3; ++a) {
    if (c.hi[a] == grid_.cells()[a]) b.hi[a] += 1;
  }
  return b;
}

int GridPartition::owner_of(const std::array<double, 3>& x) const {
  std::array<int, 3> p{};
  for (size_t a = 0; a < 3; ++a) {
    const int n = grid_.cells()[a];
    int cell = static_cast<int>(std::floor((x[a] - grid_.origin()[a]) * grid_.inverse_cell_size()));
    cell = std::clamp(cell, 0, n - 1);
    // The part whose [split(p), split(p+1)) holds the cell; the split is
    // monotone, so start from the proportional guess and correct it.
    int part = static_cast<int>(int64_t{cell} * dims_[a] / n);
    while (part > 0 && cell < split(static_cast<int>(a), part)) --part;
    while (part + 1 < dims_[a] && cell >= split(static_cast<int>(a), part + 1)) ++part;
    p[a] = part;
  }
  return rank_of(p);
}

std::vector<NodeOverlap> GridPartition::overlaps_of(int rank) const {
  std::vector<NodeOverlap> out;
  const NodeBox mine = nodes_of(rank);
  const auto& n = grid_.cells();
  for (int r = 0; r < ranks_; ++r) {
    const NodeBox theirs = nodes_of(r);
    for (int sz = -1; sz <= 1; ++sz) {
      for (int sy = -1; sy <= 1; ++sy) {
        for (int sx = -1; sx <= 1; ++sx) {
          const std::array<int, 3> s{sx, sy, sz};
          bool allowed = true;
          for (size_t a = 0; a < 3; ++a) allowed = allowed && (s[a] == 0 || periodic_[a]);
          if (!allowed || (r == rank && s == std::array<int, 3>{0, 0, 0})) continue;
          NodeBox image = theirs;
          for (size_t a = 0; a < 3; ++a) {
            image.lo[a] += s[a] * n[a];
            image.hi[a] += s[a] * n[a];
          }
          const NodeBox common = mine.intersected(image);
          if (!common.empty()) out.push_back({r, s, common});
        }
      }
    }
  }
  return out;
}

}  // namespace pbms::grid
