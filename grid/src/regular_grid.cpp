#include "pbms/grid/regular_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pbms/error.hpp"

namespace pbms::grid {

std::array<int, 3> NodeBox::extent() const {
  return {std::max(0, hi[0] - lo[0]), std::max(0, hi[1] - lo[1]), std::max(0, hi[2] - lo[2])};
}

std::int64_t NodeBox::count() const {
  const auto e = extent();
  return std::int64_t{e[0]} * e[1] * e[2];
}

bool NodeBox::empty() const {
  return count() == 0;
}

bool NodeBox::contains(const std::array<int, 3>& ijk) const {
  for (int d = 0; d < 3; ++d) {
    if (ijk[d] < lo[d] || ijk[d] >= hi[d]) return false;
  }
  return true;
}

std::int64_t NodeBox::local_index(const std::array<int, 3>& ijk) const {
  const auto e = extent();
  return (ijk[0] - lo[0]) +
         std::int64_t{e[0]} * ((ijk[1] - lo[1]) + std::int64_t{e[1]} * (ijk[2] - lo[2]));
}

std::array<int, 3> NodeBox::ijk_of_local(std::int64_t local) const {
  const auto e = extent();
  const auto i = static_cast<int>(local % e[0]);
  local /= e[0];
  const auto j = static_cast<int>(local % e[1]);
  const auto k = static_cast<int>(local / e[1]);
  return {lo[0] + i, lo[1] + j, lo[2] + k};
}

NodeBox NodeBox::grown(int layers) const {
  NodeBox b = *this;
  for (int d = 0; d < 3; ++d) {
    b.lo[d] -= layers;
    b.hi[d] += layers;
  }
  return b;
}

NodeBox NodeBox::intersected(const NodeBox& other) const {
  NodeBox b;
  for (int d = 0; d < 3; ++d) {
    b.lo[d] = std::max(lo[d], other.lo[d]);
    b.hi[d] = std::max(b.lo[d], std::min(hi[d], other.hi[d]));
  }
  return b;
}

RegularGrid::RegularGrid(const std::array<double, 3>& origin, double h,
                         const std::array<int, 3>& cells)
    : origin_(origin), h_(h), inv_h_(1.0 / h), cells_(cells) {
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw Error("grid cell size must be a positive number, got " + std::to_string(h));
  }
  for (int d = 0; d < 3; ++d) {
    if (cells[d] < 1) {
      throw Error("grid needs at least one cell along every axis, got " + std::to_string(cells[d]) +
                  " along axis " + std::to_string(d));
    }
    upper_[d] = origin[d] + h * cells[d];
  }
}

std::array<int, 3> RegularGrid::nodes_per_axis() const {
  return {cells_[0] + 1, cells_[1] + 1, cells_[2] + 1};
}

std::int64_t RegularGrid::node_count() const {
  return node_box().count();
}

std::int64_t RegularGrid::cell_count() const {
  return std::int64_t{cells_[0]} * cells_[1] * cells_[2];
}

NodeBox RegularGrid::node_box() const {
  return {{0, 0, 0}, nodes_per_axis()};
}

std::int64_t RegularGrid::node_index(const std::array<int, 3>& ijk) const {
  return node_box().local_index(ijk);
}

std::array<int, 3> RegularGrid::node_ijk(std::int64_t index) const {
  return node_box().ijk_of_local(index);
}

std::array<double, 3> RegularGrid::node_position(const std::array<int, 3>& ijk) const {
  return {origin_[0] + h_ * ijk[0], origin_[1] + h_ * ijk[1], origin_[2] + h_ * ijk[2]};
}

std::array<double, 3> RegularGrid::node_position(std::int64_t index) const {
  return node_position(node_ijk(index));
}

std::int64_t RegularGrid::cell_index(const std::array<int, 3>& cell) const {
  return cell[0] + std::int64_t{cells_[0]} * (cell[1] + std::int64_t{cells_[1]} * cell[2]);
}

bool RegularGrid::contains(const std::array<double, 3>& x) const {
  for (int d = 0; d < 3; ++d) {
    // Written so that NaN compares as outside.
    if (!(x[d] >= origin_[d] && x[d] <= upper_[d])) return false;
  }
  return true;
}

std::array<double, 3> RegularGrid::wrapped(std::array<double, 3> x,
                                           const std::array<bool, 3>& periodic) const {
  for (size_t a = 0; a < 3; ++a) {
    if (!periodic[a] || (x[a] >= origin_[a] && x[a] < upper_[a])) continue;
    const double len = upper_[a] - origin_[a];
    x[a] = origin_[a] + std::fmod(x[a] - origin_[a], len);
    if (x[a] < origin_[a]) x[a] += len;
    if (x[a] >= upper_[a]) x[a] = origin_[a];  // -tiny + len rounded up
  }
  return x;
}

std::optional<std::array<int, 3>> RegularGrid::cell_of(const std::array<double, 3>& x) const {
  if (!contains(x)) return std::nullopt;
  std::array<int, 3> c{};
  for (int d = 0; d < 3; ++d) {
    // Clamping covers the upper faces and a quotient rounded up to cells_[d]
    // for a point just inside them.
    const auto s = static_cast<int>(std::floor((x[d] - origin_[d]) * inv_h_));
    c[d] = std::clamp(s, 0, cells_[d] - 1);
  }
  return c;
}

}  // namespace pbms::grid
