#include "pbms/coupling/held_nodes.hpp"

#include <cmath>

#include "pbms/coupling/coupling_side.hpp"
#include "pbms/error.hpp"

namespace pbms::coupling {

void keep_other_sides_holds(std::span<double> summed, std::span<const double> own) {
  if (summed.size() != own.size()) {
    throw Error("held nodes: the summed records and this side's differ in size");
  }
  for (std::size_t k = 0; k + kHeldLanes <= summed.size(); k += kHeldLanes) {
    const auto mine = static_cast<int>(std::lround(own[k]));
    const int theirs = static_cast<int>(std::lround(summed[k])) - mine;
    const int keep = theirs & ~mine;
    summed[k] = keep;
    for (int a = 0; a < 3; ++a) {
      if ((keep & (1 << a)) == 0) summed[k + 1 + static_cast<std::size_t>(a)] = 0.0;
    }
  }
}

}  // namespace pbms::coupling
