#include <gtest/gtest.h>

#include <Random123/philox.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "kernels/pair_noise.hpp"
#include "kernels/philox_lanes.hpp"
#include "pbms/error.hpp"

using pbms::dpd::pair_noise;
using pbms::dpd::pair_noise_batch;
using pbms::dpd::PairNoise;
using pbms::dpd::PairNoiseDistribution;

namespace {

const PairNoise kGaussian(42, PairNoiseDistribution::kGaussian);
const PairNoise kUniform(42, PairNoiseDistribution::kUniform);

// θ from Random123's own generators and libm, for the documented layout:
// uniform θ from Philox2x32-10 keyed by key[0] + step, Gaussian θ from
// Philox4x32-10 with the step in the counter.
double reference_theta(const PairNoise& noise, std::uint32_t low, std::uint32_t high,
                       std::uint64_t step) {
  auto unit = [](std::uint32_t hi, std::uint32_t lo) {
    const std::uint64_t k = ((std::uint64_t{hi} << 32) | lo) >> 12;
    return (static_cast<double>(k) + 0.5) * 0x1.0p-52;
  };
  if (noise.distribution == PairNoiseDistribution::kUniform) {
    using Generator = r123::Philox2x32;
    const Generator::key_type key = {{noise.key[0] + static_cast<std::uint32_t>(step)}};
    const Generator::ctr_type w = Generator()({{low, high}}, key);
    return std::sqrt(3.0) * (2 * unit(w[1], w[0]) - 1);
  }
  using Generator = r123::Philox4x32;
  const Generator::key_type key = {{noise.key[0], noise.key[1]}};
  const Generator::ctr_type counter = {
      {low, high, static_cast<std::uint32_t>(step), static_cast<std::uint32_t>(step >> 32)}};
  const Generator::ctr_type w = Generator()(counter, key);
  return std::sqrt(-2.0 * std::log(unit(w[1], w[0]))) *
         std::cos(2.0 * std::numbers::pi * unit(w[3], w[2]));
}

// 37 counters: whole vectors of 16 and of 8, and a remainder.
constexpr int kCounters = 37;

void fill_counters(std::vector<std::uint32_t>& c0, std::vector<std::uint32_t>& c1) {
  c0.resize(kCounters);
  c1.resize(kCounters);
  for (int m = 0; m < kCounters; ++m) {
    c0[m] = 1000u + 17u * static_cast<std::uint32_t>(m);
    c1[m] = 0xfffffff0u - 3u * static_cast<std::uint32_t>(m);
  }
}

}  // namespace

TEST(Philox2x32Lanes, EveryPathGivesRandom123sBits) {
  using namespace pbms::dpd;
  std::vector<std::uint32_t> c0, c1;
  fill_counters(c0, c1);
  for (const std::uint32_t key : {0x01234567u, 0xfffffffeu}) {
    for (const SimdPath path : {SimdPath::kPortable, SimdPath::kAvx2, SimdPath::kAvx512}) {
      if (!simd_path_supported(path)) continue;
      std::vector<std::uint32_t> w[2];
      for (auto& word : w) word.assign(kCounters, 0);
      philox2x32_lanes(path, key, c0.data(), c1.data(), kCounters,
                       {{w[0].data(), w[1].data(), nullptr, nullptr}});
      for (int m = 0; m < kCounters; ++m) {
        const r123::Philox2x32::ctr_type ref = r123::Philox2x32()({{c0[m], c1[m]}}, {{key}});
        for (int k = 0; k < 2; ++k) {
          ASSERT_EQ(w[k][m], ref[k]) << "path " << static_cast<int>(path) << ", lane " << m;
        }
      }
    }
  }
}

TEST(Philox4x32Lanes, EveryPathGivesRandom123sBits) {
  using namespace pbms::dpd;
  const std::uint32_t key[2] = {0x01234567u, 0x89abcdefu};
  std::vector<std::uint32_t> c0, c1;
  fill_counters(c0, c1);
  for (const SimdPath path : {SimdPath::kPortable, SimdPath::kAvx2, SimdPath::kAvx512}) {
    if (!simd_path_supported(path)) continue;
    std::vector<std::uint32_t> w[4];
    for (auto& word : w) word.assign(kCounters, 0);
    philox4x32_lanes(path, key, c0.data(), c1.data(), 77u, 5u, kCounters,
                     {{w[0].data(), w[1].data(), w[2].data(), w[3].data()}});
    for (int m = 0; m < kCounters; ++m) {
      const r123::Philox4x32::ctr_type ref =
          r123::Philox4x32()({{c0[m], c1[m], 77u, 5u}}, {{key[0], key[1]}});
      for (int k = 0; k < 4; ++k) {
        ASSERT_EQ(w[k][m], ref[k]) << "path " << static_cast<int>(path) << ", lane " << m;
      }
    }
  }
}

TEST(DpdPairNoise, MatchesRandom123AndLibmForTheDocumentedLayout) {
  // The polynomial log and cos against libm: 1e-14 absolute on θ, which
  // a wrong bit anywhere in the draw would miss by orders of magnitude.
  double worst = 0.0;
  for (const PairNoise& noise : {kGaussian, kUniform}) {
    for (std::int64_t k = 0; k < 20000; ++k) {
      const std::int64_t a = 1 + k % 4000, b = 4001 + (k * 7919) % 100000;
      const std::int64_t step = (k * 104729) % (std::int64_t{1} << 40);
      const double theta = pair_noise(noise, a, b, step);
      const double ref =
          reference_theta(noise, static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
                          static_cast<std::uint64_t>(step));
      worst = std::max(worst, std::abs(theta - ref));
    }
  }
  EXPECT_LT(worst, 1e-14);
}

TEST(DpdPairNoise, BatchIsBitIdenticalToOnePairAtATime) {
  // A pair's θ must not depend on where in a batch it falls: the
  // decomposition decides that.
  for (const PairNoise& noise : {kGaussian, kUniform}) {
    for (const int count : {1, 5, 16, 37, 128, 300}) {
      std::vector<std::uint32_t> low(count), high(count);
      for (int m = 0; m < count; ++m) {
        low[m] = static_cast<std::uint32_t>(3 * m + 1);
        high[m] = static_cast<std::uint32_t>(5 * m + 1000 + count);
      }
      std::vector<double> theta(count);
      pair_noise_batch(noise, low.data(), high.data(), 12345, count, theta.data());
      for (int m = 0; m < count; ++m) {
        ASSERT_EQ(theta[m], pair_noise(noise, high[m], low[m], 12345)) << count << " " << m;
      }
    }
  }
}

TEST(DpdPairNoise, IsTheSameForBothOrdersOfThePair) {
  for (std::int64_t a = 1; a < 50; ++a) {
    for (std::int64_t b = a + 1; b < 60; b += 7) {
      for (const PairNoise& noise : {kGaussian, kUniform}) {
        EXPECT_EQ(pair_noise(noise, a, b, 1000), pair_noise(noise, b, a, 1000));
      }
    }
  }
}

TEST(DpdPairNoise, ChangesWithStepSeedAndPair) {
  const double base = pair_noise(kGaussian, 3, 8, 100);
  EXPECT_EQ(base, pair_noise(kGaussian, 3, 8, 100));  // a pure function
  EXPECT_NE(base, pair_noise(kGaussian, 3, 8, 101));
  EXPECT_NE(base, pair_noise(PairNoise(43, PairNoiseDistribution::kGaussian), 3, 8, 100));
  EXPECT_NE(base, pair_noise(kGaussian, 3, 9, 100));
  EXPECT_NE(base, pair_noise(kGaussian, 4, 8, 100));
  // Steps past 2^32 use the counter's fourth word.
  EXPECT_NE(pair_noise(kGaussian, 3, 8, 7),
            pair_noise(kGaussian, 3, 8, 7 + (std::int64_t{1} << 32)));

  const double uniform = pair_noise(kUniform, 3, 8, 100);
  EXPECT_EQ(uniform, pair_noise(kUniform, 3, 8, 100));
  EXPECT_NE(uniform, pair_noise(kUniform, 3, 8, 101));
  EXPECT_NE(uniform, pair_noise(PairNoise(43, PairNoiseDistribution::kUniform), 3, 8, 100));
  EXPECT_NE(uniform, pair_noise(kUniform, 3, 9, 100));
  EXPECT_NE(uniform, pair_noise(kUniform, 4, 8, 100));
  // The documented limit of the 32-bit key: uniform θ repeats after 2^32
  // steps.
  EXPECT_EQ(uniform, pair_noise(kUniform, 3, 8, 100 + (std::int64_t{1} << 32)));
}

TEST(DpdPairNoise, HasZeroMeanAndUnitVarianceOverAMillionDraws) {
  for (const PairNoise& noise : {kGaussian, kUniform}) {
    const int draws = 1'000'000;
    double sum = 0.0, sum_sq = 0.0, sum_4 = 0.0, lag = 0.0, previous = 0.0, largest = 0.0;
    for (int k = 0; k < draws; ++k) {
      // Pairs and steps as a run visits them: many pairs per step.
      const double g = pair_noise(noise, k % 1000, 1000 + k % 997, k / 1000);
      sum += g;
      sum_sq += g * g;
      sum_4 += g * g * g * g;
      lag += g * previous;
      previous = g;
      largest = std::max(largest, std::abs(g));
    }
    const double mean = sum / draws;
    const double variance = sum_sq / draws - mean * mean;
    // Standard errors: 1e-3 for the mean, sqrt(2)·1e-3 (Gaussian) for the
    // variance; 5 sigma.
    EXPECT_NEAR(mean, 0.0, 5e-3);
    EXPECT_NEAR(variance, 1.0, 7.1e-3);
    EXPECT_NEAR(lag / draws, 0.0, 5e-3);
    if (noise.distribution == PairNoiseDistribution::kGaussian) {
      EXPECT_NEAR(sum_4 / draws, 3.0, 0.05);  // Gaussian kurtosis, sd ~ 0.0049
      EXPECT_GT(largest, 4.0);                // P(|θ| > 4) ≈ 6e-5: ~60 draws
    } else {
      EXPECT_NEAR(sum_4 / draws, 1.8, 0.01);  // uniform: 9/5, sd ~ 0.0014
      EXPECT_LE(largest, std::sqrt(3.0));
    }
  }
}

TEST(DpdPairNoise, RefusesIdsOutside32Bits) {
  pbms::dpd::DpdParticles particles;
  particles.mass_per_type = {1.0};
  particles.add(1, 0, {0, 0, 0}, {0, 0, 0});
  EXPECT_NO_THROW(pbms::dpd::check_pair_noise_ids(particles));
  particles.add(std::int64_t{1} << 32, 0, {1, 0, 0}, {0, 0, 0});
  EXPECT_THROW(pbms::dpd::check_pair_noise_ids(particles), pbms::Error);
}
