#include "fit/parameter_uncertainty.hpp"

#include <cmath>
#include <limits>

// GCC 12 warns inside its own AVX-512 intrinsics when Eigen vectorises with
// them (GCC bug 105593, fixed in 13), as core/src/analysis/equation_of_state.cpp says.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Dense>
#pragma GCC diagnostic pop

namespace pbms::coupler::fit {

std::vector<double> parameter_errors(const std::vector<std::vector<double>>& jacobian,
                                     const std::vector<double>& sigma) {
  const auto rows = static_cast<Eigen::Index>(jacobian.size());
  const auto cols = rows > 0 ? static_cast<Eigen::Index>(jacobian[0].size()) : 0;
  std::vector<double> out(static_cast<size_t>(cols), std::numeric_limits<double>::quiet_NaN());
  if (rows < cols || cols == 0) return out;
  Eigen::MatrixXd weighted(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const double s = sigma[static_cast<size_t>(i)];
    if (!(s > 0.0) || !std::isfinite(s)) return out;
    for (Eigen::Index k = 0; k < cols; ++k) {
      weighted(i, k) = jacobian[static_cast<size_t>(i)][static_cast<size_t>(k)] / s;
    }
  }
  const Eigen::MatrixXd normal = weighted.transpose() * weighted;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
      ldlt.vectorD().minCoeff() <= 1e-14 * ldlt.vectorD().maxCoeff()) {
    return out;  // singular: some combination of parameters is not determined
  }
  const Eigen::MatrixXd cov = ldlt.solve(Eigen::MatrixXd::Identity(cols, cols));
  for (Eigen::Index k = 0; k < cols; ++k) out[static_cast<size_t>(k)] = std::sqrt(cov(k, k));
  return out;
}

}  // namespace pbms::coupler::fit
