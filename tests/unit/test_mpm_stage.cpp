// Pure parts of the mpm_run stage: the exact solution of the step-loaded
// bar and the period of an oscillating probe.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"
#include "stage/wave_front.hpp"

using namespace pbms;
using namespace pbms::mpm;

namespace {
StepLoadedBar seed_bar() {
  return {152.5, 2.5, 2000.0, 1000.0};
}
}  // namespace

TEST(StepLoadedBar, ExactStressFollowsTheReflections) {
  const auto bar = seed_bar();
  const double T = bar.transit_time();  // 0.15
  EXPECT_DOUBLE_EQ(T, 0.15);
  // First pass: the traction behind the front, nothing ahead of it.
  EXPECT_EQ(bar.exact_stress(140.0, 0.5 * T), 2000.0);
  EXPECT_EQ(bar.exact_stress(50.0, 0.5 * T), 0.0);
  // Reflected at the fixed end with the same sign: doubled behind.
  EXPECT_EQ(bar.exact_stress(10.0, 1.5 * T), 4000.0);
  EXPECT_EQ(bar.exact_stress(140.0, 1.5 * T), 2000.0);
  // Back at the loaded end, the reflection unloads to the traction.
  EXPECT_EQ(bar.exact_stress(140.0, 2.5 * T), 2000.0);
  EXPECT_EQ(bar.exact_stress(10.0, 2.5 * T), 4000.0);
  // Third transit: zero behind the front coming from the fixed end.
  EXPECT_EQ(bar.exact_stress(10.0, 3.5 * T), 0.0);
  EXPECT_EQ(bar.exact_stress(140.0, 3.5 * T), 2000.0);
  // After four transits the bar is unloaded everywhere inside.
  for (double x = 5.0; x < 152.0; x += 7.0) EXPECT_EQ(bar.exact_stress(x, 4.0 * T), 0.0);
}

TEST(StepLoadedBar, ExactProfileHasNoExcessVariationAndZeroRms) {
  const auto bar = seed_bar();
  std::vector<double> x, s, v;
  for (double xi = 2.6; xi < 152.5; xi += 0.25) {
    x.push_back(xi);
    s.push_back(bar.exact_stress(xi, 0.1));
    v.push_back(1.0);
  }
  EXPECT_EQ(rms_from_exact(bar, 0.1, x, s), 0.0);
  EXPECT_NEAR(excess_variation(bar, 0.1, x, s), 0.0, 1e-9);
  EXPECT_NEAR(front_distance(bar, x, s), 100.0, 0.25);
  EXPECT_DOUBLE_EQ(plateau_stress(bar, 0.1, x, s, v), 2000.0);
}

TEST(OscillationPeriod, RecoversTheFrequencyOfASampledCosine) {
  std::vector<double> t, y;
  for (int i = 0; i < 2000; ++i) {
    t.push_back(0.01 * i);
    y.push_back(0.3 + std::cos(2.0 * std::numbers::pi * t.back() / 3.7 + 0.4));
  }
  EXPECT_NEAR(analysis::oscillation_period(t, y), 3.7, 3.7e-4);
  EXPECT_THROW(analysis::oscillation_period({0, 1, 2}, {0, 1, 2}), pbms::Error);
}
