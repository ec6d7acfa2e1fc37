// When a sampled history first reaches a level: a slab's first motion in
// the impact analyses.
#pragma once

#include <cmath>
#include <vector>

namespace pbms::analysis {

// The time a series first exceeds `threshold`, interpolated between
// samples; NaN if it never does.
inline double first_crossing(const std::vector<double>& t, const std::vector<double>& s,
                             double threshold) {
  for (std::size_t k = 1; k < s.size(); ++k) {
    if (s[k] >= threshold && s[k - 1] < threshold) {
      return t[k - 1] + (threshold - s[k - 1]) / (s[k] - s[k - 1]) * (t[k] - t[k - 1]);
    }
  }
  return std::nan("");
}

}  // namespace pbms::analysis
