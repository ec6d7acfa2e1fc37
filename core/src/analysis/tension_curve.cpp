#include "pbms/analysis/tension_curve.hpp"

#include <algorithm>
#include <cmath>

namespace pbms::analysis {

std::vector<double> running_mean(const std::vector<double>& x, const std::vector<double>& y,
                                 double window) {
  const std::size_t n = std::min(x.size(), y.size());
  std::vector<double> out(n, 0.0);
  const double half = 0.5 * window;
  for (std::size_t k = 0; k < n; ++k) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t j = 0; j < n; ++j) {
      if (std::abs(x[j] - x[k]) <= half) {
        sum += y[j];
        ++count;
      }
    }
    out[k] = sum / count;
  }
  return out;
}

YieldPoint first_load_drop(const std::vector<double>& strain, const std::vector<double>& stress,
                           const YieldRule& rule) {
  YieldPoint yp;
  const std::size_t n = std::min(strain.size(), stress.size());
  if (n < 3) return yp;
  const std::vector<double> smooth = running_mean(strain, stress, rule.smoothing);
  std::vector<double> deviation(n);
  for (std::size_t k = 0; k < n; ++k) deviation[k] = std::abs(stress[k] - smooth[k]);
  std::nth_element(deviation.begin(), deviation.begin() + static_cast<std::ptrdiff_t>(n / 2),
                   deviation.end());
  // 1.4826 MAD is the standard deviation of a normal sample.
  yp.noise = 1.4826 * deviation[n / 2];
  const double largest = *std::max_element(smooth.begin(), smooth.end());

  std::size_t peak = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (smooth[k] > smooth[peak]) {
      peak = k;
      continue;
    }
    const double drop = std::max(rule.drop_fraction * smooth[peak], rule.noise_multiple * yp.noise);
    if (smooth[peak] - smooth[k] > drop && smooth[peak] >= rule.min_peak_fraction * largest) {
      yp.found = true;
      yp.index = peak;
      yp.stress = smooth[peak];
      yp.strain = strain[peak];
      return yp;
    }
  }
  return yp;
}

}  // namespace pbms::analysis
