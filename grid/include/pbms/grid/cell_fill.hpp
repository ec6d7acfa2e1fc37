// Material points for the MPM engine: a regular n x n x n arrangement in
// every grid cell, kept where it falls inside a region. Each point carries
// the volume of its share of the cell, so that a cell-aligned body has
// exactly its geometric volume.
#pragma once

#include <array>
#include <vector>

#include "pbms/geometry/region.hpp"
#include "pbms/grid/regular_grid.hpp"

namespace pbms::geometry {

struct MaterialPoints {
  std::vector<Vec3> positions;
  std::vector<double> volumes;  // one per position, (h / n)^3
};

// Along each axis, points sit at cell_lo + (k + 1/2) h / n, k = 0..n-1, in
// every cell of `grid`; a point is kept when region.contains() it. Points
// never lie on a cell face, so the region's boundary convention only matters
// for a region face that cuts a cell exactly there.
// Order: by z, then y, then x over the whole grid (x fastest), matching
// fill_lattice.
// Throws pbms::Error unless points_per_axis >= 1 and the region's bounds
// span at most ~1e10 candidate points.
[[nodiscard]] MaterialPoints fill_cells(const Region& region, const grid::RegularGrid& grid,
                                        int points_per_axis);
// The same with its own count per axis (a 1-D bar one cell across).
[[nodiscard]] MaterialPoints fill_cells(const Region& region, const grid::RegularGrid& grid,
                                        const std::array<int, 3>& points_per_axis);

}  // namespace pbms::geometry
