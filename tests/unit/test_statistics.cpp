#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "pbms/analysis/block_average.hpp"
#include "pbms/analysis/cubic_moduli.hpp"
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

// The block error against the truth it estimates: the scatter of the mean
// over many independent replicas of a correlated series. Each replica is a
// stationary AR(1) series x_t = phi x_{t-1} + e_t (phi = 0.9: integrated
// correlation time (1 + phi) / (2 (1 - phi)) = 9.5 samples, so a naive
// 1/sqrt(N) error is sqrt(19) = 4.4 times too small), N = 10,000 samples in
// the 10 blocks of 1,000 that md_isotherm uses.
//
// Compared: the RMS of the R block-error estimates (sqrt of the mean
// variance estimate, which is unbiased, unlike the mean of the square roots)
// and the standard deviation of the R replica means. Their ratio is 1 up to
//  - the scatter of a standard deviation from R values: 1 / sqrt(2 (R - 1));
//  - the scatter of the RMS estimate: sqrt(2 / (blocks - 1)) / 2 / sqrt(R);
//  - a bias of -0.48 % from the correlation of neighbouring blocks (exact
//    expectation of the estimator from the AR(1) autocovariance; roughly
//    phi / (1 - phi)^2 over a block variance of 1000 (1 + phi) / (1 - phi)).
// R = 4,000 makes the first two 1.1 % and 0.4 %: the ratio must be 0.995
// within 3 sigma, 3.5 %. It catches the common mistakes: dividing the block
// variance by `blocks` instead of `blocks - 1` (-5.1 %), or by sqrt(blocks)
// twice, or ignoring the correlation (-77 %). The replica scatter itself is
// checked against the exact variance of an AR(1) mean, so that a broken
// generator cannot make both sides agree.
TEST(Statistics, BlockErrorMatchesTheScatterOfIndependentReplicas) {
  constexpr int kReplicas = 4000, kSamples = 10000, kBlocks = 10;
  constexpr double kPhi = 0.9;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double stationary_sd = 1.0 / std::sqrt(1.0 - kPhi * kPhi);
  std::vector<double> x(kSamples), replica_means, block_variances;
  for (int r = 0; r < kReplicas; ++r) {
    double v = stationary_sd * noise(rng);
    for (auto& xi : x) {
      v = kPhi * v + noise(rng);
      xi = v;
    }
    replica_means.push_back(mean(x));
    const double e = block_average(x, kBlocks).error;
    block_variances.push_back(e * e);
  }
  const double grand = mean(replica_means);
  double ss = 0.0;
  for (const double m : replica_means) ss += (m - grand) * (m - grand);
  const double replica_sd = std::sqrt(ss / (kReplicas - 1));
  const double block_rms = std::sqrt(mean(block_variances));

  // Exact: Var(mean) = s^2 / N [(1 + phi) / (1 - phi) - 2 phi (1 - phi^N) / (N (1 - phi)^2)].
  const double n = kSamples;
  const double exact_sd = stationary_sd / std::sqrt(n) *
                          std::sqrt((1 + kPhi) / (1 - kPhi) - 2 * kPhi * (1 - std::pow(kPhi, n)) /
                                                                  (n * (1 - kPhi) * (1 - kPhi)));
  const double sd_sigma = 1.0 / std::sqrt(2.0 * (kReplicas - 1));
  const double rms_sigma = std::sqrt(2.0 / (kBlocks - 1)) / 2.0 / std::sqrt(double(kReplicas));
  std::printf(
      "%d AR(1) replicas: scatter of the means %.5g (exact %.5g), RMS block error %.5g "
      "(ratio %.4f), naive 1/sqrt(N) error %.5g\n",
      kReplicas, replica_sd, exact_sd, block_rms, block_rms / replica_sd,
      stationary_sd / std::sqrt(n));
  EXPECT_NEAR(replica_sd / exact_sd, 1.0, 3.0 * sd_sigma);
  EXPECT_NEAR(block_rms / replica_sd, 1.0 - 0.0048, 3.0 * std::hypot(sd_sigma, rms_sigma));
}

TEST(Statistics, BlockErrorNeedsTwoFilledBlocks) {
  EXPECT_TRUE(std::isnan(block_average({1.0, 2.0, 3.0}, 1).error));
  EXPECT_TRUE(std::isnan(block_average({1.0, 2.0, 3.0}, 10).error));
}

// The slope's block error against the scatter of the slope over independent
// replicas, as above, for a stress-strain-like curve: 200 samples of
// y = 62 x + 272 x^2 (the 298 K curve of Mishin copper, GPa) on
// x in [-0.02, 0.02], plus AR(1) noise with phi = 0.5 (integrated
// correlation time 1.5 samples; a naive error is sqrt(1/3) = 0.58 of the
// truth) of standard deviation 0.07 GPa. Expected ratio: 1 less the bias
// from the correlation of neighbouring blocks of L = 20 samples, about
// phi / ((1 - phi^2) L) = 3.3 %; the scatters of R = 4,000 replicas add
// 1.1 % and sqrt(2 / 7) / 2 / sqrt(R) = 0.4 % (1 sigma), so the ratio must
// be 0.967 within 3 sigma, 3.6 %. It catches residuals about the line
// (the x^2 term counted as noise: ratio ~1.9), the block variance taken
// with blocks - 1 degrees of freedom after a three-parameter fit (-12 %), and
// correlations ignored (0.58).
namespace {

struct ReplicaScatter {
  double mean_slope;
  double ratio;  // RMS block error over the slopes' scatter
  double sigma;  // 1 sigma of the ratio from the finite replica count
};

// 4,000 replicas of the curve below with AR(1) noise of coefficient phi.
ReplicaScatter slope_error_against_replicas(int samples, double phi) {
  constexpr int kReplicas = 4000, kBlocks = 10;
  constexpr double kSd = 0.07;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double innovation = kSd * std::sqrt(1.0 - phi * phi);
  std::vector<double> x(samples), y(samples), slopes, variances;
  for (int i = 0; i < samples; ++i) x[i] = -0.02 + 0.04 * i / (samples - 1);
  for (int r = 0; r < kReplicas; ++r) {
    double v = kSd * noise(rng);
    for (int i = 0; i < samples; ++i) {
      v = phi * v + innovation * noise(rng);
      y[i] = 62.0 * x[i] + 272.0 * x[i] * x[i] + v;
    }
    slopes.push_back(fit_line(x, y).slope);
    const double e = slope_block_error(x, y, kBlocks);
    variances.push_back(e * e);
  }
  const double m = mean(slopes);
  double ss = 0.0;
  for (const double s : slopes) ss += (s - m) * (s - m);
  const double scatter = std::sqrt(ss / (kReplicas - 1));
  const double rms = std::sqrt(mean(variances));
  std::printf("%d samples, phi %.1f: slope %.4f, scatter %.4g, RMS block error %.4g (%.4f)\n",
              samples, phi, m, scatter, rms, rms / scatter);
  const double sd_sigma = 1.0 / std::sqrt(2.0 * (kReplicas - 1));
  const double rms_sigma = std::sqrt(2.0 / (kBlocks - 3)) / 2.0 / std::sqrt(double(kReplicas));
  return {m, rms / scatter, std::hypot(sd_sigma, rms_sigma)};
}

}  // namespace

TEST(Statistics, SlopeBlockErrorMatchesTheScatterOfIndependentReplicas) {
  const ReplicaScatter r = slope_error_against_replicas(200, 0.5);
  EXPECT_NEAR(r.mean_slope, 62.0, 0.1);  // the x^2 term cancels on a window centred on 0
  EXPECT_NEAR(r.ratio, 1.0 - 0.033, 3.0 * r.sigma);
}

// 39 samples in 10 blocks: block_average keeps 30, and an error
// scaled by all 39 reads sqrt(39/30) = 1.14 times too large. White noise,
// so that neighbouring blocks are independent. With 3 samples a block the
// blocks - 3 correction for the parabola is approximate (30 samples, none
// dropped, give 1.000; dropping the end ones 1.03-1.05), so the test holds
// the ratio to 0.95-1.08: it separates counting 30 samples from 39.
TEST(Statistics, SlopeBlockErrorCountsOnlyTheSamplesItsBlocksHold) {
  const ReplicaScatter r = slope_error_against_replicas(39, 0.0);
  EXPECT_GT(r.ratio, 0.95);
  EXPECT_LT(r.ratio, 1.08);
}

TEST(Statistics, SlopeBlockErrorNeedsThreeSamplesPerBlock) {
  EXPECT_TRUE(std::isnan(slope_block_error({0, 1, 2, 3, 4}, {0, 1, 2, 3, 4}, 10)));
}

// Mishin's EAM copper (METHOD.md §6): B = 138.4 GPa, E<100> about 67 GPa;
// nu<100> = C12/(C11 + C12) and 2 C44/(C11 - C12) worked by hand.
TEST(CubicModuli, CopperRelations) {
  const pbms::analysis::CubicModuli cu{169.9, 122.6, 76.2};
  EXPECT_NEAR(cu.bulk_modulus(), 138.37, 0.01);
  EXPECT_NEAR(cu.youngs_modulus_100(), 67.13, 0.01);
  EXPECT_NEAR(cu.poisson_ratio_100(), 122.6 / 292.5, 1e-15);
  EXPECT_NEAR(cu.zener_ratio(), 152.4 / 47.3, 1e-14);
  EXPECT_NEAR(cu.tetragonal_shear_modulus(), 23.65, 1e-13);
  EXPECT_TRUE(cu.stable());
  EXPECT_FALSE((pbms::analysis::CubicModuli{100.0, 120.0, 50.0}.stable()));
}

// Eleven samples in five blocks of two (the eleventh a dropped remainder):
// block means 1.5, 3.5, ..., 9.5, their mean 5.5, the unbiased variance of
// the means 40 / 4 = 10 and the standard error sqrt(10 / 5).
TEST(BlockAverage, MeanAndErrorOfEqualBlocks) {
  std::vector<double> x;
  for (int i = 1; i <= 11; ++i) x.push_back(i);
  const auto b = block_average(x, 5);
  EXPECT_DOUBLE_EQ(b.mean, 5.5);
  EXPECT_DOUBLE_EQ(b.error, std::sqrt(2.0));
}

// Fewer samples than blocks: one sample is a static state (exact, error 0);
// more than one cannot tell its error (NaN); no samples, no mean.
TEST(BlockAverage, ShortSeries) {
  const auto one = block_average({3.0}, 5);
  EXPECT_EQ(one.mean, 3.0);
  EXPECT_EQ(one.error, 0.0);
  const auto three = block_average({1.0, 2.0, 6.0}, 5);
  EXPECT_EQ(three.mean, 3.0);
  EXPECT_TRUE(std::isnan(three.error));
  EXPECT_TRUE(std::isnan(block_average({}, 5).mean));
  EXPECT_TRUE(block_means({1.0, 2.0}, 5).empty());
}
