#include <gtest/gtest.h>

#include <cmath>

#include "pbms/analysis/quasi_static_pull.hpp"

using namespace pbms;
using namespace pbms::analysis;

namespace {

// Copper's bar wave in SI: c = sqrt(E / rho), E = 110 GPa, rho = 8.96 g/cm^3.
double copper_bar_speed_a_per_ps() {
  const double c_m_per_s = std::sqrt(110.0e9 / 8960.0);
  return c_m_per_s * 1.0e10 / 1.0e12;  // m/s to Å/ps
}

// 8.96 g/cm^3 in g/mol/Å^3: 1 g/cm^3 is 1e-24 g/Å^3, and 1 g/mol is one
// dalton, 1.66053906660e-24 g.
constexpr double kCopperDensity = 8.96 / 1.66053906660;

}  // namespace

TEST(QuasiStaticPull, PeriodsAreTheWindowOverTheBarWavesCrossingAndBack) {
  const double c = copper_bar_speed_a_per_ps();
  EXPECT_NEAR(lateral_periods(110.0, kCopperDensity, 40.0, 10.0), 10.0 * c / 80.0, 1e-6);
  EXPECT_TRUE(std::isnan(lateral_periods(-5.0, kCopperDensity, 40.0, 10.0)));
}

TEST(QuasiStaticPull, TheFitWindowEndsAtTheLastSampleWithinItsStrain) {
  const std::vector<double> strain{0.0, 0.004, 0.008, 0.012, 0.009};
  const std::vector<double> time{0.0, 1.0, 2.0, 3.0, 4.0};
  EXPECT_DOUBLE_EQ(fit_window_time(strain, time, 0.01), 4.0);
  EXPECT_DOUBLE_EQ(fit_window_time(strain, time, 0.005), 1.0);
}

TEST(QuasiStaticPull, AWindowShorterThanOneLateralPeriodIsWarnedOf) {
  // A rod 40 Å wide: a bar wave crosses it and comes back in 2 W / c.
  const double period = 2.0 * 40.0 / copper_bar_speed_a_per_ps();
  StageResults fast;
  fast.add_scalar("youngs_modulus", 110.0, "GPa");
  check_quasi_static(fast, kCopperDensity, 40.0, 0.4 * period);
  ASSERT_EQ(fast.warnings.size(), 1u);
  EXPECT_NE(fast.warnings[0].find("window lasted 0.913 ps, 0.4 of the time"), std::string::npos)
      << fast.warnings[0];

  StageResults slow;
  slow.add_scalar("youngs_modulus", 110.0, "GPa");
  check_quasi_static(slow, kCopperDensity, 40.0, 1.2 * period);
  EXPECT_TRUE(slow.warnings.empty());
  EXPECT_EQ(slow.attributes.at("fit_window_lateral_periods"), "1.2");
}

TEST(QuasiStaticPull, ANegativeModulusIsWarnedOfAndAMissingOneIsLeftAlone) {
  StageResults negative;
  negative.add_scalar("youngs_modulus", -3.0, "GPa");
  check_quasi_static(negative, kCopperDensity, 100.0, 100.0);
  ASSERT_EQ(negative.warnings.size(), 1u);
  EXPECT_NE(negative.warnings[0].find("not positive"), std::string::npos);

  StageResults none;
  check_quasi_static(none, kCopperDensity, 100.0, 100.0);
  EXPECT_TRUE(none.warnings.empty());
  EXPECT_TRUE(none.attributes.empty());
}
