#include "fit/parameter_uncertainty.hpp"

#include <algorithm>
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

double Degeneracy::condition_number() const {
  if (singular_values.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (!(singular_values.back() > 0.0)) return std::numeric_limits<double>::infinity();
  return singular_values.front() / singular_values.back();
}

Degeneracy degeneracy_of(const std::vector<std::vector<double>>& jacobian,
                         const std::vector<double>& row_scale) {
  const auto rows = static_cast<Eigen::Index>(jacobian.size());
  const auto cols = rows > 0 ? static_cast<Eigen::Index>(jacobian[0].size()) : 0;
  Degeneracy d;
  if (rows < cols || cols == 0) return d;
  Eigen::MatrixXd scaled(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index k = 0; k < cols; ++k) {
      scaled(i, k) = row_scale[static_cast<size_t>(i)] *
                     jacobian[static_cast<size_t>(i)][static_cast<size_t>(k)];
    }
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinV);
  for (Eigen::Index k = 0; k < cols; ++k) {
    d.singular_values.push_back(svd.singularValues()(k));
    std::vector<double> v(static_cast<size_t>(cols));
    for (Eigen::Index j = 0; j < cols; ++j) v[static_cast<size_t>(j)] = svd.matrixV()(j, k);
    // The sign of a singular vector is arbitrary: the largest part positive.
    const auto big = std::max_element(v.begin(), v.end(),
                                      [](double a, double b) { return std::abs(a) < std::abs(b); });
    if (*big < 0.0) {
      for (double& x : v) x = -x;
    }
    d.directions.push_back(std::move(v));
  }
  return d;
}

}  // namespace pbms::coupler::fit
