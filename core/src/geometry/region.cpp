#include "pbms/geometry/region.hpp"

#include <algorithm>

namespace pbms::geometry {

bool Box::empty() const {
  for (int d = 0; d < 3; ++d) {
    if (lo[d] > hi[d]) return true;
  }
  return false;
}

double Box::volume() const {
  double v = 1.0;
  for (int d = 0; d < 3; ++d) v *= std::max(0.0, hi[d] - lo[d]);
  return v;
}

}  // namespace pbms::geometry
