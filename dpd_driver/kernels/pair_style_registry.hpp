// Pair styles by name, in the manner of LAMMPS styles: a configuration names
// a style and gives its parameters, the registry returns the style or a
// pbms::Error a user can act on.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "kernels/pair_style.hpp"

namespace pbms::dpd {

using PairStyleFactory = std::function<std::unique_ptr<PairStyle>(const PairStyleParameters&)>;

class PairStyleRegistry {
 public:
  // Built-in styles: morse, lj_nm, table, sutton_chen. Throws pbms::Error for
  // an unknown style (listing the known ones) and for missing, unknown or
  // out-of-range parameters.
  static std::unique_ptr<PairStyle> create(std::string_view style,
                                           const PairStyleParameters& params);
  // Sorted.
  [[nodiscard]] static std::vector<std::string> names();
  [[nodiscard]] static bool contains(std::string_view style);
  // The `potential` map of a dpd_mesoparticle material (also the format of
  // a potential file): `style` and each style's own keys, as the styles
  // declare them.
  [[nodiscard]] static config::Param schema();
  // Makes a style known beyond the built-in ones. Throws pbms::Error if the
  // name is taken. Not thread-safe: call before any run.
  static void add(std::string style, PairStyleFactory factory, std::vector<config::Param> params,
                  std::string doc);
};

}  // namespace pbms::dpd
