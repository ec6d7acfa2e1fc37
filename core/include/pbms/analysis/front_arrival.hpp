// When a compression front reaches a slab, at mid-amplitude: the impact
// analyses' wave speed that a shock-speed prediction predicts.
//
// A front has a rise time (~0.1 ps over a few lattice planes for the copper
// mesoparticle), and a first-motion threshold on the displacement fires
// part-way up it, at a fraction of the rise that depends on the amplitude:
// between two slabs of different amplitude (a decaying pulse) it is biased,
// and before a weak front a slab's own drift can cross it. The point half
// way up the velocity rise moves with the front itself, the speed a jump
// condition gives.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace pbms::analysis {

struct FrontArrival {
  double time = std::nan("");       // when the velocity first reached half the amplitude
  double amplitude = std::nan("");  // the front's velocity, displacement units per time unit
};

// The centred running mean of `width` samples (fewer at the ends).
inline std::vector<double> running_mean(const std::vector<double>& x, std::size_t width) {
  std::vector<double> out(x.size(), 0.0);
  const std::size_t half = width / 2;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const std::size_t lo = k >= half ? k - half : 0;
    const std::size_t hi = std::min(x.size(), k + half + 1);
    double sum = 0.0;
    for (std::size_t j = lo; j < hi; ++j) sum += x[j];
    out[k] = sum / static_cast<double>(hi - lo);
  }
  return out;
}

// The front in a slab's displacement history s(t) (time-ordered samples):
// the velocity ds/dt between samples, smoothed over `smoothing` (a time;
// thermal jitter of a thin slab is ~0.1–0.3 Å/ps), has its front's top at
// its largest value within `window` of `first_motion` (the time the
// displacement first passed a threshold, which lies on or just past the
// rise). The amplitude is that value and the arrival the last time before
// it that the smoothed velocity rose through half of it, interpolated.
// NaN for a NaN first_motion or fewer than 3 samples.
inline FrontArrival mid_amplitude_arrival(const std::vector<double>& t,
                                          const std::vector<double>& s, double first_motion,
                                          double smoothing, double window) {
  FrontArrival a;
  if (std::isnan(first_motion) || t.size() < 3 || s.size() != t.size()) return a;
  std::vector<double> tm(t.size() - 1), v(t.size() - 1);
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    tm[k] = 0.5 * (t[k] + t[k + 1]);
    v[k] = (s[k + 1] - s[k]) / (t[k + 1] - t[k]);
  }
  const double dt = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  const auto width = static_cast<std::size_t>(std::max(1.0, std::round(smoothing / dt)));
  const std::vector<double> vs = running_mean(v, width);
  std::size_t top = vs.size();
  for (std::size_t k = 0; k < vs.size(); ++k) {
    if (std::abs(tm[k] - first_motion) > window) continue;
    if (top == vs.size() || vs[k] > vs[top]) top = k;
  }
  if (top == vs.size() || !(vs[top] > 0.0)) return a;
  const double half = 0.5 * vs[top];
  std::size_t j = top;
  while (j > 0 && vs[j - 1] >= half) --j;
  if (j == 0) return a;
  a.amplitude = vs[top];
  a.time = tm[j - 1] + (half - vs[j - 1]) / (vs[j] - vs[j - 1]) * (tm[j] - tm[j - 1]);
  return a;
}

}  // namespace pbms::analysis
