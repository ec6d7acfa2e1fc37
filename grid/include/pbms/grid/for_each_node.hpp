// Visits the nodes of a box in the order of NodeBox::local_index (i
// fastest): the order both sides of a node exchange pack and unpack in.
#pragma once

#include <array>

#include "pbms/grid/regular_grid.hpp"

namespace pbms::grid {

template <typename F>
void for_each_node(const NodeBox& box, F&& f) {
  for (int k = box.lo[2]; k < box.hi[2]; ++k)
    for (int j = box.lo[1]; j < box.hi[1]; ++j)
      for (int i = box.lo[0]; i < box.hi[0]; ++i) f(std::array<int, 3>{i, j, k});
}

}  // namespace pbms::grid
