#include "pbms/coupling/interface_band.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::coupling {
namespace {

geometry::Box grown(geometry::Box b, double margin) {
  for (std::size_t a = 0; a < 3; ++a) {
    b.lo[a] -= margin;
    b.hi[a] += margin;
  }
  return b;
}

}  // namespace

InterfaceBand::InterfaceBand(const grid::RegularGrid& grid, const geometry::Region& a,
                             const geometry::Region& b, double margin)
    : grid_(grid) {
  const geometry::Box ga = grown(a.bounds(), margin), gb = grown(b.bounds(), margin);
  for (std::size_t x = 0; x < 3; ++x) {
    box_.lo[x] = std::max(ga.lo[x], gb.lo[x]);
    box_.hi[x] = std::min(ga.hi[x], gb.hi[x]);
  }
  if (box_.empty()) {
    throw Error(fmt::format(
        "interface band: the two regions do not come within {:g} Å of each other, so nothing "
        "would cross between the programs",
        margin));
  }
  // The nodes of every cell the band box touches (a linear stencil's).
  const double inv = grid.inverse_cell_size();
  for (std::size_t x = 0; x < 3; ++x) {
    const int n = grid.cells()[x];
    const double lo = (box_.lo[x] - grid.origin()[x]) * inv;
    const double hi = (box_.hi[x] - grid.origin()[x]) * inv;
    nodes_.lo[x] = std::clamp(static_cast<int>(std::floor(lo)), 0, n);
    nodes_.hi[x] = std::clamp(static_cast<int>(std::floor(hi)) + 2, 0, n + 1);
  }
  if (nodes_.empty()) throw Error("interface band: the band lies outside the grid");
}

bool InterfaceBand::covers(const geometry::Vec3& x) const {
  // The cell of x (its stencil's lower corner) and the one above.
  bool inside = true, outside = false;
  const double inv = grid_.inverse_cell_size();
  for (std::size_t a = 0; a < 3; ++a) {
    const int c = static_cast<int>(std::floor((x[a] - grid_.origin()[a]) * inv));
    inside = inside && c >= nodes_.lo[a] && c + 1 < nodes_.hi[a];
    outside = outside || c + 1 < nodes_.lo[a] || c >= nodes_.hi[a];
  }
  return inside || outside;
}

}  // namespace pbms::coupling
