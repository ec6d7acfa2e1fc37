// The pulse speed of the impact analyses (pbms/analysis/level_delays.hpp) on
// displacement histories built here: a pulse that keeps its shape, one that
// spreads between the slabs, and one the far slab never sees.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pbms/analysis/level_delays.hpp"

using namespace pbms::analysis;

namespace {

constexpr double kSpeed = 33.0;  // Å/ps, about a copper mesoparticle rod's bar speed
constexpr double kStep = 0.01;   // ps, dpd_run's sampling

std::vector<double> times() {
  std::vector<double> t;
  for (int k = 0; k <= 800; ++k) t.push_back(k * kStep);
  return t;
}

// A slab at x under a displacement that rises smoothly to `amplitude`
// around t = x / kSpeed over a time `width`.
std::vector<double> slab(double x, double width, double amplitude) {
  std::vector<double> s;
  for (const double time : times()) {
    s.push_back(0.5 * amplitude * (1.0 + std::erf((time - x / kSpeed) / width)));
  }
  return s;
}

}  // namespace

TEST(LevelDelays, APulseOfOneShapeGivesItsSpeedAtEveryLevel) {
  const LevelDelays d =
      level_delays(times(), slab(100.0, 0.8, 1.0), slab(150.0, 0.8, 1.0), 0.05, 0.4, 8);
  ASSERT_EQ(d.levels.size(), 8u);
  EXPECT_DOUBLE_EQ(d.levels.front(), 0.05);
  EXPECT_NEAR(d.levels.back(), 0.4, 1e-15);
  EXPECT_NEAR(d.levels[1] / d.levels[0], std::pow(8.0, 1.0 / 7.0), 1e-12);
  for (const double delay : d.delays) EXPECT_NEAR(50.0 / delay / kSpeed, 1.0, 2e-3);
  EXPECT_NEAR(50.0 / d.mean() / kSpeed, 1.0, 1e-3);
}

// A rise that widens between the slabs (dispersion): low levels arrive
// early at the far slab, high levels late, so the delay grows with the
// level; the levels symmetric about mid-amplitude keep the mean delay.
TEST(LevelDelays, ASpreadingPulseDelaysItsHighLevelsMore) {
  const LevelDelays d =
      level_delays(times(), slab(100.0, 0.5, 1.0), slab(150.0, 0.9, 1.0), 0.2, 0.8, 2);
  EXPECT_LT(d.delays[0], 50.0 / kSpeed);
  EXPECT_GT(d.delays[1], 50.0 / kSpeed);
  EXPECT_NEAR(50.0 / d.mean() / kSpeed, 1.0, 2e-3);
}

TEST(LevelDelays, ALevelTheFarSlabNeverReachesHasNoMean) {
  const LevelDelays d =
      level_delays(times(), slab(100.0, 0.8, 1.0), slab(150.0, 0.8, 0.3), 0.05, 0.4, 8);
  EXPECT_FALSE(std::isnan(d.delays.front()));
  EXPECT_TRUE(std::isnan(d.delays.back()));
  EXPECT_TRUE(std::isnan(d.mean()));
}
