#include "pbms/analysis/statistics.hpp"

#include "pbms/analysis/block_average.hpp"

#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::analysis {

double mean(const std::vector<double>& x) {
  if (x.empty()) throw Error("mean of an empty series");
  return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
}

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  if (n < 3 || y.size() != n) throw Error("a line fit needs at least 3 (x, y) points");
  const double mx = mean(x), my = mean(y);
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (sxx <= 0.0) throw Error("a line fit needs at least two distinct x values");
  LineFit f;
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  double rss = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double r = y[i] - (f.slope * x[i] + f.intercept);
    rss += r * r;
  }
  f.slope_error = std::sqrt(rss / static_cast<double>(n - 2) / sxx);
  f.r2 = syy > 0.0 ? 1.0 - rss / syy : 1.0;
  return f;
}

namespace {

// Residuals of y about its least-squares parabola in u = x - mean(x); the
// 3x3 normal equations are solved by Cramer's rule (well conditioned once
// centred).
std::vector<double> residuals_about_parabola(const std::vector<double>& x,
                                             const std::vector<double>& y) {
  const double mx = mean(x);
  double m[5] = {}, b[3] = {};  // m[k] = sum u^k, b[k] = sum u^k y
  for (size_t i = 0; i < x.size(); ++i) {
    const double u = x[i] - mx;
    double uk = 1.0;
    for (int k = 0; k < 5; ++k, uk *= u) {
      m[k] += uk;
      if (k < 3) b[k] += uk * y[i];
    }
  }
  auto det3 = [](double a, double b1, double c, double d, double e, double f, double g, double h,
                 double i) {
    return a * (e * i - f * h) - b1 * (d * i - f * g) + c * (d * h - e * g);
  };
  const double d = det3(m[0], m[1], m[2], m[1], m[2], m[3], m[2], m[3], m[4]);
  const double c0 = det3(b[0], m[1], m[2], b[1], m[2], m[3], b[2], m[3], m[4]) / d;
  const double c1 = det3(m[0], b[0], m[2], m[1], b[1], m[3], m[2], b[2], m[4]) / d;
  const double c2 = det3(m[0], m[1], b[0], m[1], m[2], b[1], m[2], m[3], b[2]) / d;
  std::vector<double> r(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    const double u = x[i] - mx;
    r[i] = y[i] - (c0 + c1 * u + c2 * u * u);
  }
  return r;
}

}  // namespace

double slope_block_error(const std::vector<double>& x, const std::vector<double>& y, int blocks) {
  const size_t n = x.size();
  if (y.size() != n || blocks < 4 || n < 3 * static_cast<size_t>(blocks)) return std::nan("");
  const double mx = mean(x);
  double sxx = 0.0;
  for (double v : x) sxx += (v - mx) * (v - mx);
  if (sxx <= 0.0) return std::nan("");
  // block_se^2 * used is the variance per sample that the correlations
  // leave, where `used` counts the samples block_average keeps (it
  // drops the remainder of n / blocks). It divides by blocks - 1, right for
  // a mean; the parabola took three parameters from the same residuals, so
  // blocks - 3 (without it the error is sqrt(7/9), 12 %, low on white noise
  // with 10 blocks).
  const double se = block_average(residuals_about_parabola(x, y), blocks).error;
  const double used = static_cast<double>(n / static_cast<size_t>(blocks) * blocks);
  const double dof = static_cast<double>(blocks - 1) / static_cast<double>(blocks - 3);
  return se * std::sqrt(used * dof / sxx);
}

double oscillation_period(const std::vector<double>& t, const std::vector<double>& y) {
  if (t.size() != y.size()) throw Error("oscillation_period: t and y differ in length");
  const double m = y.empty() ? 0.0 : mean(y);
  std::vector<double> up;
  for (size_t i = 1; i < y.size(); ++i) {
    const double a = y[i - 1] - m, b = y[i] - m;
    if (a < 0.0 && b >= 0.0) up.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-a) / (b - a));
  }
  if (up.size() < 2) {
    throw Error(
        fmt::format("oscillation_period: the signal crosses its mean upwards {} time(s); "
                    "run longer or sample more often",
                    up.size()));
  }
  return (up.back() - up.front()) / static_cast<double>(up.size() - 1);
}

}  // namespace pbms::analysis
