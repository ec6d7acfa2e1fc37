#include "pbms/analysis/block_average.hpp"

#include <cmath>
#include <cstddef>
#include <limits>

namespace pbms::analysis {

std::vector<double> block_means(const std::vector<double>& x, int blocks) {
  if (blocks < 1) return {};
  const std::size_t per = x.size() / static_cast<std::size_t>(blocks);
  if (per == 0) return {};
  std::vector<double> means(static_cast<std::size_t>(blocks), 0.0);
  for (std::size_t b = 0; b < means.size(); ++b) {
    for (std::size_t k = 0; k < per; ++k) means[b] += x[b * per + k];
    means[b] /= static_cast<double>(per);
  }
  return means;
}

BlockAverage average_of_blocks(const std::vector<double>& means) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (means.empty()) return {nan, nan};
  BlockAverage r;
  for (const double m : means) r.mean += m;
  r.mean /= static_cast<double>(means.size());
  if (means.size() < 2) return r;
  double variance = 0.0;
  for (const double m : means) variance += (m - r.mean) * (m - r.mean);
  variance /= static_cast<double>(means.size() - 1);
  r.error = std::sqrt(variance / static_cast<double>(means.size()));
  return r;
}

BlockAverage block_average(const std::vector<double>& x, int blocks) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (blocks < 2 || x.empty()) return {nan, nan};
  const std::vector<double> means = block_means(x, blocks);
  if (!means.empty()) return average_of_blocks(means);
  BlockAverage r = average_of_blocks(x);  // the mean of all samples
  if (x.size() > 1) r.error = nan;
  return r;
}

}  // namespace pbms::analysis
