// Standard errors of fitted parameters from the sampling errors of what the
// judge measured: weighted least squares about the best point,
// cov = (J^T W J)^-1 with W = diag(1 / sigma_i^2), J the derivative of the
// fitted residuals with respect to the parameters.
#pragma once

#include <vector>

namespace pbms::coupler::fit {

// `jacobian` has one row per residual and one column per parameter; `sigma`
// one standard error per residual. NaN for every parameter when a sigma is
// not positive or J^T W J is singular.
std::vector<double> parameter_errors(const std::vector<std::vector<double>>& jacobian,
                                     const std::vector<double>& sigma);

// How well the targets determine the parameters about the best point: the
// singular values of the Jacobian of the residuals, each row scaled as the
// objective weighs it (the objective is then the squared norm), with
// respect to the parameters in the unit box of their bounds; largest first.
// Each direction is a unit vector in that box. A direction whose singular
// value is small beside the largest moves the parameters without moving the
// residuals: the targets do not determine it (two different parameter sets
// give nearly the same targets).
struct Degeneracy {
  std::vector<double> singular_values;
  std::vector<std::vector<double>> directions;  // one per singular value
  // Largest over smallest singular value (infinite when the smallest is 0).
  [[nodiscard]] double condition_number() const;
};

// Empty when the Jacobian has fewer rows than columns or none.
Degeneracy degeneracy_of(const std::vector<std::vector<double>>& jacobian,
                         const std::vector<double>& row_scale);

}  // namespace pbms::coupler::fit
