// An impact analysis's baseline against the run it is subtracted from
// (pbms/analysis/baseline_covers.hpp).
#include <gtest/gtest.h>

#include <vector>

#include "pbms/analysis/baseline_covers.hpp"

using pbms::analysis::baseline_covers;

namespace {

std::vector<double> every_step(int samples, double dt) {
  std::vector<double> t;
  for (int k = 0; k < samples; ++k) t.push_back(k * dt);
  return t;
}

}  // namespace

TEST(BaselineCovers, TheSameStepsOrMoreAtTheSameLength) {
  EXPECT_TRUE(baseline_covers(every_step(601, 0.01), 600, 0.01));
  EXPECT_TRUE(baseline_covers(every_step(601, 0.01), 550, 0.01));
  EXPECT_FALSE(baseline_covers(every_step(551, 0.01), 600, 0.01));
  EXPECT_FALSE(baseline_covers(every_step(601, 0.005), 600, 0.01));
  EXPECT_TRUE(baseline_covers(every_step(1, 0.01), 0, 0.01));
}
