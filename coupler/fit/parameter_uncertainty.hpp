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

}  // namespace pbms::coupler::fit
