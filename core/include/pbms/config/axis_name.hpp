// An axis as a config names it ("x", "y" or "z", which the schema's choice
// parameters hold it to) as the index 0, 1 or 2.
#pragma once

#include <string_view>

namespace pbms::config {

[[nodiscard]] inline int axis_index(std::string_view axis) {
  return axis == "x" ? 0 : axis == "y" ? 1 : 2;
}

}  // namespace pbms::config
