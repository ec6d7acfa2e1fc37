// Shape functions of the MPM grid and the registry that selects them by name.
// A solver asks the registry for a style and never names a concrete class, so
// GIMP or quadratic B-splines arrive as new classes plus one registry line.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "pbms/grid/regular_grid.hpp"

namespace pbms::grid {

// Every node a shape function weights at one point, with the weights and
// their spatial gradients. A whole stencil per call keeps the virtual call
// out of the inner node loop; the fixed capacity keeps particle loops free of
// allocation. 27 = 3x3x3 nodes, enough for GIMP and quadratic B-splines.
struct ShapeStencil {
  static constexpr int kMaxNodes = 27;

  int count = 0;
  std::array<std::int64_t, kMaxNodes> node{};  // linear node indices
  std::array<double, kMaxNodes> N{};
  std::array<std::array<double, 3>, kMaxNodes> dN{};  // gradient of N, 1/length
};

class ShapeFunction {
 public:
  virtual ~ShapeFunction() = default;

  // Fills `out` for the point x. Throws pbms::Error when x is outside the
  // grid: a material point that left the grid is a failed run, not a zero.
  virtual void evaluate(const RegularGrid& grid, const std::array<double, 3>& x,
                        ShapeStencil& out) const = 0;
  // The most nodes evaluate() ever returns (at most ShapeStencil::kMaxNodes).
  [[nodiscard]] virtual int support_nodes() const = 0;
  // The registry name, as a user writes it in a config.
  [[nodiscard]] virtual std::string_view name() const = 0;
};

// Styles by name, in the manner of LAMMPS styles. The built-in styles are
// listed in shape_function.cpp rather than registered by static objects,
// which a static library would silently drop at link time.
class ShapeFunctionRegistry {
 public:
  using Factory = std::function<std::unique_ptr<ShapeFunction>()>;

  // Throws pbms::Error naming the available styles when `name` is unknown.
  static std::unique_ptr<ShapeFunction> create(std::string_view name);
  // Sorted.
  [[nodiscard]] static std::vector<std::string> names();
  [[nodiscard]] static bool contains(std::string_view name);
  // Makes a style known beyond the built-in ones (a plugin, a test). Throws
  // pbms::Error if the name is taken. Not thread-safe: call before any run.
  static void add(std::string name, Factory factory);
};

}  // namespace pbms::grid
