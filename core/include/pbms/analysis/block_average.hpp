// Mean and standard error of a correlated series (a thermostatted run's
// pressure, a stress sampled along a strain ramp) by blocking: the series
// is cut into equal blocks long against its correlation time, and the
// scatter of their means gives the error (Flyvbjerg & Petersen 1989, one
// level). The one implementation every stage uses.
#pragma once

#include <vector>

namespace pbms::analysis {

struct BlockAverage {
  double mean = 0.0;
  double error = 0.0;  // one standard error
};

// The means of `blocks` equal blocks of x; a remainder of fewer than
// `blocks` samples is dropped, so that the blocks are equal. Empty when x
// has fewer samples than blocks.
[[nodiscard]] std::vector<double> block_means(const std::vector<double>& x, int blocks);

// The mean of a set of block means and its standard error, sqrt(var / n)
// with the unbiased variance of the n means. One block: error 0 (its
// samples are one static state, exact); none: NaN for both.
[[nodiscard]] BlockAverage average_of_blocks(const std::vector<double>& means);

// average_of_blocks(block_means(x, blocks)). A series of fewer samples
// than blocks has no error estimate: its mean is all samples', its error
// NaN, but for a single sample (a static state): error 0. NaN for both
// when blocks < 2 or x is empty.
[[nodiscard]] BlockAverage block_average(const std::vector<double>& x, int blocks);

}  // namespace pbms::analysis
