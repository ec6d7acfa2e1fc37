// Trilinear tent functions: the 8 nodes of the cell that holds the point,
// N_i(x) = prod_d (1 - |x_d - X_i,d| / h). The shape function of the seed's
// MPM (§2.4.2); its gradient jumps on cell faces, which is what DDMP smooths.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <type_traits>

#include "pbms/grid/shape_function.hpp"

namespace pbms::grid {

// The stencil of the linear style with its node count fixed at compile time,
// so that a solver's loops over it unroll (same fields as ShapeStencil).
struct LinearStencil {
  static constexpr int count = 8;
  std::array<std::int64_t, 8> node{};
  std::array<double, 8> N{};
  std::array<std::array<double, 3>, 8> dN{};
};

class ShapeFunctionLinear final : public ShapeFunction {
 public:
  // The evaluation for one grid with the grid's constants taken once: an
  // inline path for solvers that check for this style once per step.
  // evaluate() runs the same arithmetic, so both give identical results.
  class Kernel {
   public:
    explicit Kernel(const RegularGrid& grid)
        : origin_(grid.origin()),
          h_(grid.cell_size()),
          inv_h_(1.0 / grid.cell_size()),
          last_cell_(grid.cells()),
          stride_y_(grid.nodes_per_axis()[0]),
          stride_z_(std::int64_t{grid.nodes_per_axis()[0]} * grid.nodes_per_axis()[1]) {
      for (auto& c : last_cell_) c -= 1;
    }

    // x must lie in the grid (RegularGrid::contains); Stencil is
    // LinearStencil or ShapeStencil.
    template <class Stencil>
    [[gnu::always_inline]] void operator()(const std::array<double, 3>& x, Stencil& out) const {
      // Per axis: weights and slopes of the lower (0) and upper (1) node. The
      // cell is RegularGrid::cell_of's (x >= origin, so truncation is floor);
      // the clamp keeps round-off in the local coordinate from pushing N out
      // of [0, 1].
      double w[3][2];
      int cell[3];
      for (int d = 0; d < 3; ++d) {
        const double r = x[d] - origin_[d];
        cell[d] = std::clamp(static_cast<int>(r / h_), 0, last_cell_[d]);
        const double xi = std::clamp(r * inv_h_ - cell[d], 0.0, 1.0);
        w[d][0] = 1.0 - xi;
        w[d][1] = xi;
      }
      const double s[2] = {-inv_h_, inv_h_};
      const std::int64_t base = cell[0] + stride_y_ * cell[1] + stride_z_ * cell[2];
      if constexpr (!std::is_same_v<Stencil, LinearStencil>) out.count = 8;
      for (int c = 0; c < 2; ++c) {
        for (int b = 0; b < 2; ++b) {
          for (int a = 0; a < 2; ++a) {
            const int q = a + 2 * b + 4 * c;
            out.node[q] = base + a + b * stride_y_ + c * stride_z_;
            out.N[q] = w[0][a] * w[1][b] * w[2][c];
            out.dN[q] = {s[a] * w[1][b] * w[2][c], w[0][a] * s[b] * w[2][c],
                         w[0][a] * w[1][b] * s[c]};
          }
        }
      }
    }

   private:
    std::array<double, 3> origin_;
    double h_, inv_h_;
    std::array<int, 3> last_cell_;
    std::int64_t stride_y_, stride_z_;
  };

  // Nodes come in the cell's corner order, x offset fastest: node a + 2b + 4c
  // is the corner (cx + a, cy + b, cz + c).
  void evaluate(const RegularGrid& grid, const std::array<double, 3>& x,
                ShapeStencil& out) const override;
  [[nodiscard]] int support_nodes() const override { return 8; }
  [[nodiscard]] std::string_view name() const override { return "linear"; }
};

}  // namespace pbms::grid
