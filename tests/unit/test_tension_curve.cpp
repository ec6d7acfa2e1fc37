#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "pbms/analysis/tension_curve.hpp"

using namespace pbms::analysis;

namespace {

// A rod's curve: linear to a peak at strain 0.14, then a fall of 30 % over
// 0.01 of strain and a flat tail; early ringing and Gaussian noise added.
void noisy_rod(double noise, std::vector<double>& strain, std::vector<double>& stress) {
  std::mt19937_64 gen(7);
  std::normal_distribution<double> g(0.0, noise);
  for (int k = 0; k <= 800; ++k) {
    const double e = 0.0002 * k;
    double s = e <= 0.14 ? 90.0 * e : std::max(0.7 * 12.6, 12.6 - 378.0 * (e - 0.14));
    s += 0.5 * std::exp(-e / 0.01) * std::sin(e / 0.002);
    strain.push_back(e);
    stress.push_back(s + g(gen));
  }
}

}  // namespace

TEST(TensionCurve, RunningMeanOfALineIsTheLineInside) {
  std::vector<double> x, y;
  for (int k = 0; k < 50; ++k) {
    x.push_back(0.1 * k);
    y.push_back(3.0 * x.back() + 1.0);
  }
  const auto m = running_mean(x, y, 0.45);
  for (int k = 2; k < 48; ++k) EXPECT_NEAR(m[k], y[k], 1e-12);
}

TEST(TensionCurve, FirstLoadDropFindsThePeakThroughNoise) {
  std::vector<double> strain, stress;
  noisy_rod(0.15, strain, stress);
  const YieldPoint y = first_load_drop(strain, stress, YieldRule{});
  ASSERT_TRUE(y.found);
  // The smoothing window (0.005) rounds the cusp by about a quarter of it
  // times the slopes on either side.
  EXPECT_NEAR(y.strain, 0.14, 0.003);
  EXPECT_NEAR(y.stress, 12.6, 0.25);
  EXPECT_NEAR(y.noise, 0.15, 0.03);
}

TEST(TensionCurve, EarlyRingingAndAPlateauAreNoYield) {
  std::vector<double> strain, stress;
  for (int k = 0; k <= 400; ++k) {
    const double e = 0.0005 * k;
    strain.push_back(e);
    // Rings by 10 % at low stress, then flattens out at 12 GPa.
    stress.push_back(std::min(12.0, 90.0 * e) + 0.1 * std::sin(e / 0.001));
  }
  EXPECT_FALSE(first_load_drop(strain, stress, YieldRule{}).found);
}

TEST(TensionCurve, AFallSmallerThanTheNoiseIsNoDrop) {
  std::vector<double> strain, stress;
  noisy_rod(2.0, strain, stress);
  YieldRule rule;
  rule.drop_fraction = 0.01;
  // 3 sigma = 6 GPa exceeds the 30 % (3.8 GPa) fall.
  EXPECT_FALSE(first_load_drop(strain, stress, rule).found);
}
