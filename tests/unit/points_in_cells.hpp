// Material points on a regular sub-lattice of grid cells, for the solver
// tests.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "pbms/grid/material_points.hpp"
#include "pbms/grid/regular_grid.hpp"

namespace pbms::test {

// n x n x n points per cell at the centres of the cell's n^3 sub-cells, in
// every cell of [lo, hi), each with state s and its sub-cell's volume.
inline void fill_cells(grid::MaterialPoints& pts, const grid::RegularGrid& g, std::array<int, 3> lo,
                       std::array<int, 3> hi, int n, const grid::MaterialPointState& s) {
  const double h = g.cell_size();
  for (int k = lo[2]; k < hi[2]; ++k)
    for (int j = lo[1]; j < hi[1]; ++j)
      for (int i = lo[0]; i < hi[0]; ++i)
        for (int c = 0; c < n; ++c)
          for (int b = 0; b < n; ++b)
            for (int a = 0; a < n; ++a) {
              pts.add(static_cast<std::int64_t>(pts.size()),
                      {h * (i + (a + 0.5) / n), h * (j + (b + 0.5) / n), h * (k + (c + 0.5) / n)},
                      std::pow(h / n, 3), s, 0);
            }
}

}  // namespace pbms::test
