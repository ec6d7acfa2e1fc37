// Trilinear tent functions: the 8 nodes of the cell that holds the point,
// N_i(x) = prod_d (1 - |x_d - X_i,d| / h). The shape function of the seed's
// MPM (§2.4.2); its gradient jumps on cell faces, which is what DDMP smooths.
#pragma once

#include "pbms/grid/shape_function.hpp"

namespace pbms::grid {

class ShapeFunctionLinear final : public ShapeFunction {
 public:
  // Nodes come in the cell's corner order, x offset fastest: node a + 2b + 4c
  // is the corner (cx + a, cy + b, cz + c).
  void evaluate(const RegularGrid& grid, const std::array<double, 3>& x,
                ShapeStencil& out) const override;
  [[nodiscard]] int support_nodes() const override { return 8; }
  [[nodiscard]] std::string_view name() const override { return "linear"; }
};

}  // namespace pbms::grid
