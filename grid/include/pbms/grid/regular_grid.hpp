// The MPM background grid: a box of identical cubic cells. Pure geometry, no
// fields; the solver keeps nodal arrays indexed by the linear node index.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

namespace pbms::grid {

// A box of nodes in global (i, j, k) node indices, half-open: lo <= ijk < hi.
// It names the part of the grid a rank owns plus its ghost layers, so that
// nodal arrays can be stored per box and still be addressed globally.
struct NodeBox {
  std::array<int, 3> lo{};
  std::array<int, 3> hi{};

  [[nodiscard]] std::array<int, 3> extent() const;
  [[nodiscard]] std::int64_t count() const;  // 0 when empty
  [[nodiscard]] bool empty() const;
  [[nodiscard]] bool contains(const std::array<int, 3>& ijk) const;
  // Index within the box, i fastest; ijk must lie in the box.
  [[nodiscard]] std::int64_t local_index(const std::array<int, 3>& ijk) const;
  [[nodiscard]] std::array<int, 3> ijk_of_local(std::int64_t local) const;
  // The box widened by `layers` nodes on every side (ghost layers); clip the
  // result to the grid with intersected(grid.node_box()).
  [[nodiscard]] NodeBox grown(int layers) const;
  [[nodiscard]] NodeBox intersected(const NodeBox& other) const;

  bool operator==(const NodeBox&) const = default;
};

class RegularGrid {
 public:
  // Throws pbms::Error unless h > 0 and every axis has at least one cell.
  RegularGrid(const std::array<double, 3>& origin, double h, const std::array<int, 3>& cells);

  [[nodiscard]] const std::array<double, 3>& origin() const { return origin_; }
  [[nodiscard]] double cell_size() const { return h_; }
  // 1 / h, rounded once: every cell lookup scales by it (a multiply instead
  // of a division in the particle loops), so all of them agree on which
  // cell a point near a face is in.
  [[nodiscard]] double inverse_cell_size() const { return inv_h_; }
  [[nodiscard]] const std::array<int, 3>& cells() const { return cells_; }
  [[nodiscard]] std::array<int, 3> nodes_per_axis() const;
  [[nodiscard]] std::int64_t node_count() const;
  [[nodiscard]] std::int64_t cell_count() const;
  // The corner opposite the origin.
  [[nodiscard]] const std::array<double, 3>& upper() const { return upper_; }
  // Every node of the grid, as a box.
  [[nodiscard]] NodeBox node_box() const;

  // Linear node index, i fastest; the same order as node_box().local_index.
  [[nodiscard]] std::int64_t node_index(const std::array<int, 3>& ijk) const;
  [[nodiscard]] std::array<int, 3> node_ijk(std::int64_t index) const;
  [[nodiscard]] std::array<double, 3> node_position(const std::array<int, 3>& ijk) const;
  [[nodiscard]] std::array<double, 3> node_position(std::int64_t index) const;
  // Linear cell index, i fastest over cells().
  [[nodiscard]] std::int64_t cell_index(const std::array<int, 3>& cell) const;

  // The grid is the closed box [origin, upper]: points on the upper faces are
  // inside, so that material touching the far wall still maps to nodes.
  [[nodiscard]] bool contains(const std::array<double, 3>& x) const;
  // x moved back into [origin, upper) along the axes marked periodic; the
  // other axes are left alone.
  [[nodiscard]] std::array<double, 3> wrapped(std::array<double, 3> x,
                                              const std::array<bool, 3>& periodic) const;
  // The cell holding x, or nothing when x is outside: floor((x - origin)
  // * inverse_cell_size()). A point on a face between two cells belongs to
  // the upper one where that product is exact (and to either within
  // round-off otherwise), except on the grid's upper faces, where it
  // belongs to the last cell.
  [[nodiscard]] std::optional<std::array<int, 3>> cell_of(const std::array<double, 3>& x) const;

 private:
  std::array<double, 3> origin_;
  double h_;
  double inv_h_;
  std::array<int, 3> cells_;
  std::array<double, 3> upper_;
};

}  // namespace pbms::grid
