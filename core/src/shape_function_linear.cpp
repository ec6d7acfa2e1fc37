#include "pbms/grid/shape_function_linear.hpp"

#include <algorithm>
#include <string>

#include "pbms/error.hpp"

namespace pbms::grid {

void ShapeFunctionLinear::evaluate(const RegularGrid& grid, const std::array<double, 3>& x,
                                   ShapeStencil& out) const {
  const auto cell = grid.cell_of(x);
  if (!cell) {
    throw Error("point (" + std::to_string(x[0]) + ", " + std::to_string(x[1]) + ", " +
                std::to_string(x[2]) + ") is outside the MPM grid");
  }
  const double h = grid.cell_size();
  const double inv_h = 1.0 / h;
  // Per axis: weights and slopes of the lower (0) and upper (1) node. The
  // clamp keeps round-off in the local coordinate from pushing N out of [0, 1].
  std::array<std::array<double, 2>, 3> w{};
  std::array<std::array<double, 2>, 3> s{};
  for (int d = 0; d < 3; ++d) {
    const double xi = std::clamp((x[d] - grid.origin()[d]) * inv_h - (*cell)[d], 0.0, 1.0);
    w[d] = {1.0 - xi, xi};
    s[d] = {-inv_h, inv_h};
  }
  const std::int64_t base = grid.node_index(*cell);
  const auto n = grid.nodes_per_axis();
  const std::int64_t stride_y = n[0];
  const std::int64_t stride_z = std::int64_t{n[0]} * n[1];
  out.count = 8;
  for (int c = 0; c < 2; ++c) {
    for (int b = 0; b < 2; ++b) {
      for (int a = 0; a < 2; ++a) {
        const int q = a + 2 * b + 4 * c;
        out.node[q] = base + a + b * stride_y + c * stride_z;
        out.N[q] = w[0][a] * w[1][b] * w[2][c];
        out.dN[q] = {s[0][a] * w[1][b] * w[2][c], w[0][a] * s[1][b] * w[2][c],
                     w[0][a] * w[1][b] * s[2][c]};
      }
    }
  }
}

}  // namespace pbms::grid
