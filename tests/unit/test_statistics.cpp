#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "md_elastic.hpp"
#include "pbms/analysis/equation_of_state.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"

using namespace pbms::analysis;

TEST(EquationOfState, RecoversBirchMurnaghanParameters) {
  // Copper-like: V0 = 11.97 Å^3, B0 = 1.35e6 bar, B0' = 4.8.
  std::vector<double> v, p;
  for (double x = 0.90; x <= 1.001; x += 0.02) {
    v.push_back(11.97 * x);
    p.push_back(birch_murnaghan_pressure(11.97 * x, 11.97, 1.35e6, 4.8));
  }
  const auto fit = fit_birch_murnaghan(v, p);
  EXPECT_NEAR(fit.v0, 11.97, 1e-8);
  EXPECT_NEAR(fit.b0 / 1.35e6, 1.0, 1e-8);
  EXPECT_NEAR(fit.b0_prime, 4.8, 1e-6);
  EXPECT_LT(fit.rms_residual, 1e-3);
}

TEST(EquationOfState, PressureVanishesAtV0AndSlopeIsB0) {
  EXPECT_NEAR(birch_murnaghan_pressure(10.0, 10.0, 1e6, 4.5), 0.0, 1e-9);
  const double h = 1e-6;
  const double dpdv = (birch_murnaghan_pressure(10.0 + h, 10.0, 1e6, 4.5) -
                       birch_murnaghan_pressure(10.0 - h, 10.0, 1e6, 4.5)) /
                      (2 * h);
  EXPECT_NEAR(-10.0 * dpdv / 1e6, 1.0, 1e-6);
}

TEST(EquationOfState, NeedsThreePoints) {
  EXPECT_THROW(fit_birch_murnaghan({1.0, 2.0}, {1.0, 0.0}), pbms::Error);
}

TEST(Statistics, LineFitIsExactOnALine) {
  const auto f = fit_line({0, 1, 2, 3}, {1, 3, 5, 7});
  EXPECT_NEAR(f.slope, 2.0, 1e-12);
  EXPECT_NEAR(f.intercept, 1.0, 1e-12);
  EXPECT_NEAR(f.slope_error, 0.0, 1e-12);
}

TEST(Statistics, BlockErrorMatchesWhiteNoise) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x(100000);
  for (auto& v : x) v = g(rng);
  // Uncorrelated samples: the standard error is 1/sqrt(N) within its own
  // sampling scatter (10 blocks -> ~24 % relative).
  EXPECT_NEAR(block_standard_error(x, 10) * std::sqrt(1e5), 1.0, 0.6);
}

TEST(CubicElasticity, CopperRelations) {
  EXPECT_NEAR(pbms::md::cubic_bulk_modulus(169.9, 122.6), 138.37, 0.01);
  EXPECT_NEAR(pbms::md::cubic_youngs_modulus_100(169.9, 122.6), 67.13, 0.01);
}
