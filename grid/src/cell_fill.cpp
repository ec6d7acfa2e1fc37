#include "pbms/grid/cell_fill.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::geometry {

namespace {

// As in lattice_fill.cpp: a guard against a region in the wrong units.
constexpr double kMaxCandidatePoints = 1e10;

}  // namespace

MaterialPoints fill_cells(const Region& region, const grid::RegularGrid& grid,
                          int points_per_axis) {
  return fill_cells(region, grid, {points_per_axis, points_per_axis, points_per_axis});
}

MaterialPoints fill_cells(const Region& region, const grid::RegularGrid& grid,
                          const std::array<int, 3>& points_per_axis) {
  for (const int n : points_per_axis) {
    if (n < 1) {
      throw Error(fmt::format("material points per cell and axis must be at least 1, got {}", n));
    }
  }
  MaterialPoints out;
  const Box b = region.bounds();
  if (b.empty()) return out;

  // Points along axis d have a global index s = cell * n + k over the whole
  // grid; only the index range that can reach the region's box is visited,
  // widened by one against rounding. NaN or infinite bounds fall back to the
  // whole grid through the comparisons in max/min.
  const double h = grid.cell_size();
  std::array<std::vector<double>, 3> coordinate;
  double candidates = 1.0;
  double volume = 1.0;
  for (int d = 0; d < 3; ++d) {
    const int n = points_per_axis[static_cast<size_t>(d)];
    const double step = h / n;
    volume *= step;
    const double total = static_cast<double>(grid.cells()[d]) * n;
    const double lo = std::max(0.0, std::floor((b.lo[d] - grid.origin()[d]) / step) - 1.0);
    const double hi = std::min(total, std::ceil((b.hi[d] - grid.origin()[d]) / step) + 1.0);
    if (!(lo < hi)) return out;
    candidates *= hi - lo;
    if (!(candidates <= kMaxCandidatePoints)) {
      throw Error(fmt::format(
          "filling with {} material points per cell and axis would test more than {:g} points; "
          "check the region's units or the points per cell",
          n, kMaxCandidatePoints));
    }
    // Cell corner as the grid computes node positions, plus the offset
    // within the cell, so that points sit symmetrically in every cell.
    for (auto s = static_cast<std::int64_t>(lo); s < static_cast<std::int64_t>(hi); ++s) {
      const std::int64_t cell = s / n;
      const std::int64_t k = s % n;
      coordinate[d].push_back(grid.origin()[d] + h * static_cast<double>(cell) +
                              (static_cast<double>(k) + 0.5) * step);
    }
  }

  for (const double z : coordinate[2]) {
    for (const double y : coordinate[1]) {
      for (const double x : coordinate[0]) {
        const Vec3 p{x, y, z};
        if (!region.contains(p)) continue;
        out.positions.push_back(p);
        out.volumes.push_back(volume);
      }
    }
  }
  return out;
}

}  // namespace pbms::geometry
