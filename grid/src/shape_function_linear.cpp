#include "pbms/grid/shape_function_linear.hpp"

#include <string>

#include "pbms/error.hpp"

namespace pbms::grid {

void ShapeFunctionLinear::evaluate(const RegularGrid& grid, const std::array<double, 3>& x,
                                   ShapeStencil& out) const {
  if (!grid.contains(x)) {
    throw Error("point (" + std::to_string(x[0]) + ", " + std::to_string(x[1]) + ", " +
                std::to_string(x[2]) + ") is outside the MPM grid");
  }
  const Kernel kernel(grid);
  kernel(x, out);
}

}  // namespace pbms::grid
