// The impact analyses' mid-amplitude arrival (pbms/analysis/front_arrival.hpp)
// on fronts built here: a tanh velocity rise of known speed and amplitude,
// sampled as a slab's displacement every 0.01 ps as dpd_run records it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pbms/analysis/first_crossing.hpp"
#include "pbms/analysis/front_arrival.hpp"

using namespace pbms::analysis;

namespace {

constexpr double kSpeed = 46.0;  // Å/ps
constexpr double kRise = 0.03;   // ps: v rises from 12 % to 88 % of u in 4 kRise
constexpr double kStep = 0.01;   // ps

// Displacement of a slab at x (Å) under v(t) = u/2 (1 + tanh((t − x/U)/τ)),
// the integral u/2 (t' + τ ln cosh(t'/τ)) from t = 0.
std::vector<double> displacement(double x, double u, const std::vector<double>& t) {
  const auto integral = [&](double time) {
    const double tp = time - x / kSpeed;
    return 0.5 * u * (tp + kRise * std::log(std::cosh(tp / kRise)));
  };
  std::vector<double> s;
  for (const double time : t) s.push_back(integral(time) - integral(0.0));
  return s;
}

std::vector<double> times() {
  std::vector<double> t;
  for (int k = 0; k <= 450; ++k) t.push_back(k * kStep);
  return t;
}

struct Speeds {
  double first_motion, mid_amplitude;
};

Speeds speeds(double u_near, double u_far) {
  const std::vector<double> t = times();
  const auto near = displacement(100.0, u_near, t);
  const auto far = displacement(150.0, u_far, t);
  const double fm_near = first_crossing(t, near, 0.25);
  const double fm_far = first_crossing(t, far, 0.25);
  const FrontArrival a = mid_amplitude_arrival(t, near, fm_near, 0.05, 0.1);
  const FrontArrival b = mid_amplitude_arrival(t, far, fm_far, 0.05, 0.1);
  EXPECT_NEAR(a.amplitude, u_near, 0.01 * u_near);
  EXPECT_NEAR(b.amplitude, u_far, 0.01 * u_far);
  return {50.0 / (fm_far - fm_near), 50.0 / (b.time - a.time)};
}

}  // namespace

// A steady front: both times give its speed; half way up to within the
// interpolation between samples (the smoothing is symmetric, so it shifts
// both slabs alike).
TEST(FrontArrival, SteadyFrontGivesItsSpeed) {
  const Speeds s = speeds(1.5, 1.5);
  EXPECT_NEAR(s.mid_amplitude / kSpeed, 1.0, 2e-3);
  EXPECT_NEAR(s.first_motion / kSpeed, 1.0, 2e-3);
}

// A decaying front (1.85 then 1.5 Å/ps, as the dpd_impact flyer's): the
// 0.25 Å threshold takes 0.25/1.5 − 0.25/1.85 = 0.03 ps longer behind the
// weaker far front, and reads ~3 % slow; half way up does not see the
// amplitude.
TEST(FrontArrival, DecayingFrontBiasesFirstMotionOnly) {
  const Speeds s = speeds(1.85, 1.5);
  EXPECT_NEAR(s.mid_amplitude / kSpeed, 1.0, 2e-3);
  EXPECT_LT(s.first_motion / kSpeed, 0.98);
}

TEST(FrontArrival, NoFirstMotionNoArrival) {
  const std::vector<double> t = times();
  const FrontArrival a =
      mid_amplitude_arrival(t, std::vector<double>(t.size(), 0.0), std::nan(""), 0.05, 0.1);
  EXPECT_TRUE(std::isnan(a.time));
  EXPECT_TRUE(std::isnan(a.amplitude));
}
