#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/branch_free_exp.hpp"

using pbms::dpd::branch_free_exp;

TEST(DpdBranchFreeExp, AgreesWithStdExpToAFewUlp) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> wide(-708.0, 708.0);
  std::uniform_real_distribution<double> pair_range(-20.0, 20.0);
  double worst = 0.0;
  for (int k = 0; k < 200000; ++k) {
    const double x = k % 2 == 0 ? wide(rng) : pair_range(rng);
    const double exact = std::exp(x);
    worst = std::max(worst, std::abs(branch_free_exp(x) - exact) / exact);
  }
  EXPECT_LT(worst, 5e-16);
  EXPECT_EQ(branch_free_exp(0.0), 1.0);
  EXPECT_NEAR(branch_free_exp(1.0), std::exp(1.0), 4e-16 * std::exp(1.0));
}
