#include "pbms/analysis/rod_bend.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace pbms::analysis {

namespace {

// Half the median slab's members: an end face relaxed out past the last
// whole slab leaves a few particles there, whose centroid may stand a
// radius off the axis (a rod of the surface-fitted copper read 17.7 Å of
// bend on its first sample where its centre line was straight to 3 Å).
double fewest_members(const std::vector<std::array<double, 4>>& slabs) {
  std::vector<double> counts;
  for (const auto& s : slabs) {
    if (s[0] > 0.0) counts.push_back(s[0]);
  }
  if (counts.empty()) return 0.0;
  const auto mid = counts.begin() + static_cast<std::ptrdiff_t>(counts.size() / 2);
  std::nth_element(counts.begin(), mid, counts.end());
  return 0.5 * *mid;
}

}  // namespace

double rod_bend(const std::vector<std::array<double, 4>>& slabs) {
  const double fewest = fewest_members(slabs);
  std::vector<std::array<double, 3>> line;
  for (const auto& s : slabs) {
    if (s[0] > 0.0 && s[0] >= fewest) line.push_back({s[1] / s[0], s[2] / s[0], s[3] / s[0]});
  }
  if (line.size() < 3) return 0.0;
  const auto& p = line.front();
  const auto& q = line.back();
  std::array<double, 3> u{q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  const double length = std::hypot(u[0], u[1], u[2]);
  for (double& c : u) c /= length;
  double bend = 0.0;
  for (const auto& c : line) {
    const std::array<double, 3> d{c[0] - p[0], c[1] - p[1], c[2] - p[2]};
    // |d × u|: the distance from the chord, without the cancellation of
    // |d|² - (d·u)².
    bend = std::max(bend, std::hypot(d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2],
                                     d[0] * u[1] - d[1] * u[0]));
  }
  return bend;
}

}  // namespace pbms::analysis
