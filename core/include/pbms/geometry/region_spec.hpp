// Regions as plain data, and the registry that builds them by style name, so
// that a config reader maps its input onto RegionSpec and never names a
// Region class. The styles and their parameters:
//
//   block         lo: [x, y, z]   hi: [x, y, z]
//   sphere        centre: [x, y, z]   radius: [r]
//   cylinder      axis: x | y | z (a word)   centre: [c1, c2]   radius: [r]
//                 lo: [l]   hi: [h]   (centre in increasing axis order, see
//                 CylinderRegion)
//   union         two or more children
//   intersection  two or more children
//   difference    two or more children: the first minus all the others
//
// Every parameter is required and no other is accepted: a misspelt key is an
// error, not a silently ignored default.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "pbms/geometry/region.hpp"

namespace pbms::geometry {

struct RegionSpec {
  std::string style;
  std::map<std::string, std::vector<double>> params;  // numbers, a scalar as one element
  std::map<std::string, std::string> words;           // word-valued, e.g. a cylinder's axis
  std::vector<RegionSpec> children;                   // of union, intersection, difference
};

// Styles by name, as ShapeFunctionRegistry. Built-in styles are listed in
// region_spec.cpp rather than registered by static objects, which a static
// library would silently drop at link time.
class RegionRegistry {
 public:
  // A factory reads the spec's params, words and children; RegionRegistry
  // prefixes its errors with the style (and child position when nested).
  using Factory = std::function<std::unique_ptr<Region>(const RegionSpec&)>;

  // Throws pbms::Error for an unknown style (naming the available ones), a
  // missing, unknown or wrongly sized parameter (naming it and the style's
  // parameters), a wrong number of children, or an invalid shape.
  static std::unique_ptr<Region> create(const RegionSpec& spec);
  // Sorted.
  [[nodiscard]] static std::vector<std::string> names();
  [[nodiscard]] static bool contains(std::string_view style);
  // Makes a style known beyond the built-in ones. Throws pbms::Error if the
  // name is taken. Not thread-safe: call before any run.
  static void add(std::string style, Factory factory);
};

}  // namespace pbms::geometry
