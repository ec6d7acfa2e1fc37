// Small statistics kernels used by several stages: means, line fits and
// their errors, periods (block averages: block_average.hpp).
#pragma once

#include <vector>

namespace pbms::analysis {

double mean(const std::vector<double>& x);

struct LineFit {
  double slope = 0.0, intercept = 0.0;
  double slope_error = 0.0;  // one standard error
  double r2 = 0.0;
};
// Ordinary least squares y = slope * x + intercept. Needs >= 3 points.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

// Standard error of fit_line's slope when the noise in y is correlated in
// sample order (a stress sampled along a strain ramp): the variance per
// sample comes from `blocks` block means of the residuals (block_average). The residuals are taken
// about a least-squares parabola, so that a curve's bend is not counted as noise. Needs blocks >= 4
// and at least 3 points per block; NaN otherwise.
double slope_block_error(const std::vector<double>& x, const std::vector<double>& y,
                         int blocks = 10);

// Period of an oscillating sample y(t): the mean spacing of its upward
// crossings of its mean, each located by linear interpolation. Throws
// pbms::Error with fewer than two crossings.
double oscillation_period(const std::vector<double>& t, const std::vector<double>& y);

}  // namespace pbms::analysis
