#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "kernels/pair_noise.hpp"

using pbms::dpd::pair_gaussian_pair_noise;

TEST(DpdPairNoise, IsTheSameForBothOrdersOfThePair) {
  for (std::int64_t a = 1; a < 50; ++a) {
    for (std::int64_t b = a + 1; b < 60; b += 7) {
      EXPECT_EQ(pair_gaussian_pair_noise(42, a, b, 1000), pair_gaussian_pair_noise(42, b, a, 1000));
    }
  }
}

TEST(DpdPairNoise, ChangesWithStepSeedAndPair) {
  const double base = pair_gaussian_pair_noise(42, 3, 8, 100);
  EXPECT_EQ(base, pair_gaussian_pair_noise(42, 3, 8, 100));  // a pure function
  EXPECT_NE(base, pair_gaussian_pair_noise(42, 3, 8, 101));
  EXPECT_NE(base, pair_gaussian_pair_noise(43, 3, 8, 100));
  EXPECT_NE(base, pair_gaussian_pair_noise(42, 3, 9, 100));
  EXPECT_NE(base, pair_gaussian_pair_noise(42, 4, 8, 100));
}

TEST(DpdPairNoise, HasZeroMeanAndUnitVarianceOverAMillionDraws) {
  const int draws = 1'000'000;
  double sum = 0.0, sum_sq = 0.0, sum_4 = 0.0, lag = 0.0, previous = 0.0;
  for (int k = 0; k < draws; ++k) {
    // Pairs and steps as a run visits them: many pairs per step.
    const double g = pair_gaussian_pair_noise(2024, k % 1000, 1000 + k % 997, k / 1000);
    sum += g;
    sum_sq += g * g;
    sum_4 += g * g * g * g;
    lag += g * previous;
    previous = g;
  }
  const double mean = sum / draws;
  const double variance = sum_sq / draws - mean * mean;
  // Standard errors: 1e-3 for the mean, sqrt(2)·1e-3 for the variance; 5 sigma.
  EXPECT_NEAR(mean, 0.0, 5e-3);
  EXPECT_NEAR(variance, 1.0, 7.1e-3);
  EXPECT_NEAR(sum_4 / draws, 3.0, 0.05);  // Gaussian kurtosis, sd ~ 0.0049
  EXPECT_NEAR(lag / draws, 0.0, 5e-3);
}
