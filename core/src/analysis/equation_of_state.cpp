#include "pbms/analysis/equation_of_state.hpp"

#include <cmath>

// GCC 12 warns inside its own AVX-512 intrinsics when Eigen vectorises with
// them (GCC bug 105593, fixed in 13); the warning is not about our code.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Core>
#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>
#pragma GCC diagnostic pop

#include "pbms/error.hpp"

namespace pbms::analysis {

double birch_murnaghan_pressure(double v, double v0, double b0, double b0_prime) {
  const double x = std::cbrt(v0 / v);  // (V0/V)^(1/3)
  const double x2 = x * x;
  const double x5 = x2 * x2 * x;
  const double x7 = x5 * x2;
  return 1.5 * b0 * (x7 - x5) * (1.0 + 0.75 * (b0_prime - 4.0) * (x2 - 1.0));
}

namespace {

// Parameters are scaled to O(1) so that the finite-difference Jacobian and the
// LM step control work equally on volumes (~10 Å^3) and pressures (~1e6 bar).
struct Residuals {
  using Scalar = double;
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };

  const std::vector<double>& v;
  const std::vector<double>& p;
  double v_scale, p_scale;

  [[nodiscard]] int inputs() const { return 3; }
  [[nodiscard]] int values() const { return static_cast<int>(v.size()); }
  int operator()(const Eigen::VectorXd& q, Eigen::VectorXd& r) const {
    for (size_t i = 0; i < v.size(); ++i) {
      r[static_cast<Eigen::Index>(i)] =
          (birch_murnaghan_pressure(v[i], q[0] * v_scale, q[1] * p_scale, q[2]) - p[i]) / p_scale;
    }
    return 0;
  }
};

}  // namespace

EosFit fit_birch_murnaghan(const std::vector<double>& volumes,
                           const std::vector<double>& pressures) {
  const size_t n = volumes.size();
  if (n < 3 || pressures.size() != n) {
    throw Error("an equation-of-state fit needs at least 3 (volume, pressure) points");
  }
  // Start from the lowest-pressure point and a finite-difference modulus.
  size_t lo = 0, hi = 0;
  for (size_t i = 1; i < n; ++i) {
    if (pressures[i] < pressures[lo]) lo = i;
    if (pressures[i] > pressures[hi]) hi = i;
  }
  const double b_guess = -(pressures[hi] - pressures[lo]) / std::log(volumes[hi] / volumes[lo]);
  if (!(b_guess > 0.0)) throw Error("EOS fit: volume does not decrease with pressure");
  const double v_scale = volumes[lo];
  const double p_scale = b_guess;

  Residuals f{volumes, pressures, v_scale, p_scale};
  Eigen::NumericalDiff<Residuals> diff(f);
  Eigen::LevenbergMarquardt<Eigen::NumericalDiff<Residuals>> lm(diff);
  lm.parameters.xtol = 1e-14;
  lm.parameters.ftol = 1e-14;
  lm.parameters.maxfev = 20000;
  Eigen::VectorXd q(3);
  q << 1.0 + pressures[lo] / b_guess, 1.0, 4.0;
  const auto status = lm.minimize(q);
  if (status < 0 || !std::isfinite(q[0]) || q[1] <= 0.0) {
    throw Error("EOS fit did not converge");
  }
  EosFit fit;
  fit.v0 = q[0] * v_scale;
  fit.b0 = q[1] * p_scale;
  fit.b0_prime = q[2];
  double ss = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double r =
        birch_murnaghan_pressure(volumes[i], fit.v0, fit.b0, fit.b0_prime) - pressures[i];
    ss += r * r;
  }
  fit.rms_residual = std::sqrt(ss / static_cast<double>(n));
  return fit;
}

}  // namespace pbms::analysis
