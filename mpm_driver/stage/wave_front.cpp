#include "wave_front.hpp"

#include <algorithm>
#include <cmath>

#include "pbms/error.hpp"

namespace pbms::mpm {

double StepLoadedBar::length() const {
  return std::abs(loaded_end - fixed_end);
}

double StepLoadedBar::exact_stress(double x, double t) const {
  const double L = length();
  const double s = std::clamp(std::abs(x - loaded_end), 0.0, L);  // distance from the load
  const double ct = wave_speed * t;
  // Wave k = 0, 1, ... leaves the loaded end at ct = 2kL with sign (-1)^k and
  // comes back from the fixed end with the same sign.
  double sigma = 0.0;
  for (int k = 0; 2.0 * k * L <= ct; ++k) {
    const double sign = (k % 2 == 0) ? 1.0 : -1.0;
    if (ct >= 2.0 * k * L + s) sigma += sign;
    if (ct >= 2.0 * (k + 1) * L - s) sigma += sign;
  }
  return traction * sigma;
}

double front_distance(const StepLoadedBar& bar, const std::vector<double>& x,
                      const std::vector<double>& stress) {
  double front = 0.0;
  for (size_t p = 0; p < x.size(); ++p) {
    if (stress[p] / bar.traction > 0.5) front = std::max(front, std::abs(x[p] - bar.loaded_end));
  }
  return front;
}

double rms_from_exact(const StepLoadedBar& bar, double t, const std::vector<double>& x,
                      const std::vector<double>& stress) {
  if (x.empty()) throw Error("wave_front: the bar has no points");
  double ss = 0.0;
  for (size_t p = 0; p < x.size(); ++p) {
    const double d = stress[p] - bar.exact_stress(x[p], t);
    ss += d * d;
  }
  return std::sqrt(ss / static_cast<double>(x.size()));
}

double excess_variation(const StepLoadedBar& bar, double t, const std::vector<double>& x,
                        const std::vector<double>& stress) {
  std::vector<size_t> order(x.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return x[a] < x[b]; });
  double tv = 0.0, tv_exact = 0.0;
  for (size_t k = 1; k < order.size(); ++k) {
    const size_t a = order[k - 1], b = order[k];
    tv += std::abs(stress[b] - stress[a]);
    tv_exact += std::abs(bar.exact_stress(x[b], t) - bar.exact_stress(x[a], t));
  }
  return tv - tv_exact;
}

double plateau_stress(const StepLoadedBar& bar, double t, const std::vector<double>& x,
                      const std::vector<double>& stress, const std::vector<double>& volume) {
  const double L = bar.length();
  const double front = bar.wave_speed * t;
  double sum = 0.0, vol = 0.0;
  for (size_t p = 0; p < x.size(); ++p) {
    const double s = std::abs(x[p] - bar.loaded_end);
    if (s > 0.1 * L && s < front - 0.1 * L) {
      sum += volume[p] * stress[p];
      vol += volume[p];
    }
  }
  if (!(vol > 0.0)) throw Error("wave_front: no point lies on the plateau behind the front");
  return sum / vol;
}

}  // namespace pbms::mpm
