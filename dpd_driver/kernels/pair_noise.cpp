#include "kernels/pair_noise.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string>

#include "kernels/philox_lanes.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

namespace {

using Word = std::uint32_t;
using Wide = std::uint64_t;

// ---- From output words to θ ---------------------------------------------
// Exact integer-to-double steps, correctly rounded +, ×, ÷, sqrt and
// explicit std::fma only (the build passes -ffp-contract=off, so the
// compiler fuses nothing on its own): a value has the same bits in any
// vector lane, in scalar code and on any x86-64 (std::fma is exact
// everywhere; where the processor has no FMA unit it is slower, not
// different).

constexpr Wide kExponentOne = 0x3ff0000000000000ULL;  // bits of 1.0
constexpr Wide kMagic = 0x4330000000000000ULL;        // bits of 2^52
constexpr Wide kMantissa = 0x000fffffffffffffULL;

inline Wide join(Word high, Word low) {
  return (Wide{high} << 32) | low;
}

// (k + ½) 2^-52 for the top 52 bits k of a 64-bit word: in (0, 1), never 0,
// so its log is finite. 1 + k 2^-52 is exact, and so is subtracting 1 and
// adding 2^-53.
inline double open_unit(Wide bits) {
  return (std::bit_cast<double>(kExponentOne | (bits >> 12)) - 1.0) + 0x1p-53;
}

// Σ coefficient[i] x^(N−1−i) by Horner's rule, one exact fma per term.
// Forced inline: a target clone below does not inline a callee built for
// another target on its own, and a call per lane would stop the loop from
// vectorising (2.3× slower).
template <std::size_t N>
[[gnu::always_inline]] inline double horner(double x, const std::array<double, N>& coefficient) {
  double p = coefficient[0];
  for (std::size_t i = 1; i < N; ++i) p = std::fma(p, x, coefficient[i]);
  return p;
}

// log u for a normal u in (0, 1): u = m 2^e with m in [√½, √2), log m =
// 2 atanh(s), s = (m − 1)/(m + 1), |s| ≤ 0.1716; ten terms of the atanh
// series leave under 3e-17 relative.
inline double log_open_unit(double u) {
  const Wide bits = std::bit_cast<Wide>(u);
  double m = std::bit_cast<double>((bits & kMantissa) | kExponentOne);
  // The biased exponent as an exact double, without an int-to-double
  // conversion that SSE2 and AVX2 cannot vectorise.
  double e = (std::bit_cast<double>(kMagic | (bits >> 52)) - 0x1p52) - 1023.0;
  // Halve m above √2 by arithmetic, not a branch: a scalar branch on a
  // random bit mispredicts half the time.
  const double high = m > 1.4142135623730951 ? 1.0 : 0.0;
  m *= 1.0 - 0.5 * high;
  e += high;
  const double s = (m - 1.0) / (m + 1.0);
  const double z = s * s;
  // 2 Σ_{k ≤ 9} z^k / (2k + 1), highest power first.
  constexpr std::array<double, 10> kAtanhSeries = {2.0 / 19, 2.0 / 17, 2.0 / 15, 2.0 / 13, 2.0 / 11,
                                                   2.0 / 9,  2.0 / 7,  2.0 / 5,  2.0 / 3,  2.0};
  const double p = horner(z, kAtanhSeries);
  // ln 2 split so that e · ln2_high is exact (fdlibm's constants).
  constexpr double kLn2High = 6.93147180369123816490e-01;
  constexpr double kLn2Low = 1.90821492927058770002e-10;
  return e * kLn2High + (e * kLn2Low + s * p);
}

// cos 2πt for t = (k + ½) 2^-52, k the top 52 bits of a word. The quadrant q
// = round(4t) and the remainder y = t − q/4, |y| ≤ 1/8, come exactly from
// integers; then cos 2πt = ±cos φ or ±sin φ of φ = 2πy, |φ| ≤ π/4, whose
// Taylor series (to φ^18 and φ^17) leave under 1e-17.
inline double cos_two_pi(Wide bits) {
  const Wide k = bits >> 12;
  const Wide q = (k + (Wide{1} << 49)) >> 50;  // 0 … 4
  // k − q 2^50 lies in [−2^49, 2^49); shifted by 2^50 it is a positive
  // integer below 2^52, which the magic constant turns into a double.
  const Wide shifted = k + (Wide{1} << 50) - (q << 50);
  const double d = (std::bit_cast<double>(kMagic | shifted) - 0x1p52) - 0x1p50;
  const double phi = (d + 0.5) * (0x1p-52 * 6.283185307179586477);
  const double minus_z = -(phi * phi);
  // cos φ = Σ_{k ≤ 9} (−z)^k / (2k)!, sin φ = φ Σ_{k ≤ 8} (−z)^k / (2k + 1)!.
  constexpr std::array<double, 10> kCosineSeries = {1.0 / 6402373705728000,
                                                    1.0 / 20922789888000,
                                                    1.0 / 87178291200,
                                                    1.0 / 479001600,
                                                    1.0 / 3628800,
                                                    1.0 / 40320,
                                                    1.0 / 720,
                                                    1.0 / 24,
                                                    1.0 / 2,
                                                    1.0};
  constexpr std::array<double, 9> kSineSeries = {1.0 / 355687428096000,
                                                 1.0 / 1307674368000,
                                                 1.0 / 6227020800,
                                                 1.0 / 39916800,
                                                 1.0 / 362880,
                                                 1.0 / 5040,
                                                 1.0 / 120,
                                                 1.0 / 6,
                                                 1.0};
  const double c = horner(minus_z, kCosineSeries);
  const double s = phi * horner(minus_z, kSineSeries);
  // cos(φ + qπ/2) = cos φ, −sin φ, −cos φ, sin φ, cos φ for q = 0 … 4,
  // chosen with bit masks rather than branches.
  const Wide pick_sine = Wide{0} - (q & 1);
  const Wide negate = ((q + 1) & 2) << 62;
  const Wide value = (std::bit_cast<Wide>(s) & pick_sine) | (std::bit_cast<Wide>(c) & ~pick_sine);
  return std::bit_cast<double>(value ^ negate);
}

__attribute__((target_clones("arch=skylake-avx512", "arch=haswell", "default"))) void
gaussian_from_words(const Word* w0, const Word* w1, const Word* w2, const Word* w3, int count,
                    double* theta) {
  for (int m = 0; m < count; ++m) {
    const double u = open_unit(join(w1[m], w0[m]));
    theta[m] = std::sqrt(-2.0 * log_open_unit(u)) * cos_two_pi(join(w3[m], w2[m]));
  }
}

__attribute__((target_clones("arch=skylake-avx512", "arch=haswell", "default"))) void
uniform_from_words(const Word* w0, const Word* w1, int count, double* theta) {
  constexpr double kSqrt3 = 1.7320508075688772;
  for (int m = 0; m < count; ++m) {
    theta[m] = kSqrt3 * (2.0 * open_unit(join(w1[m], w0[m])) - 1.0);
  }
}

Wide splitmix64(Wide x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

}  // namespace

PairNoiseDistribution pair_noise_distribution(std::string_view name) {
  if (name == "gaussian") return PairNoiseDistribution::kGaussian;
  if (name == "uniform") return PairNoiseDistribution::kUniform;
  throw Error("DPD noise: unknown distribution '" + std::string(name) +
              "' (known: gaussian, uniform)");
}

PairNoise::PairNoise(std::uint64_t seed, PairNoiseDistribution distribution_)
    : distribution(distribution_) {
  const Wide mixed = splitmix64(seed ^ kDpdPairNoiseStream);
  key[0] = static_cast<Word>(mixed);
  key[1] = static_cast<Word>(mixed >> 32);
}

void pair_noise_batch(const PairNoise& noise, const std::uint32_t* id_low,
                      const std::uint32_t* id_high, std::int64_t step, int count, double* theta) {
  // The transforms run over whole vectors of 16 (the words past count are
  // zero-filled and their values dropped), so no pair is left to a scalar
  // remainder loop.
  constexpr int kChunk = 128;
  constexpr int kLanes = 16;
  alignas(64) Word words[4][kChunk];
  alignas(64) double values[kChunk];
  const PhiloxLaneOutput out{{words[0], words[1], words[2], words[3]}};
  const SimdPath path = fastest_simd_path();
  const auto step_bits = static_cast<Wide>(step);
  const auto step0 = static_cast<Word>(step_bits);
  const auto step1 = static_cast<Word>(step_bits >> 32);
  const Word uniform_key = noise.uniform_key(step);
  for (int b = 0; b < count; b += kChunk) {
    const int n = std::min(kChunk, count - b);
    const int padded = (n + kLanes - 1) / kLanes * kLanes;
    if (noise.distribution == PairNoiseDistribution::kGaussian) {
      philox4x32_lanes(path, noise.key, id_low + b, id_high + b, step0, step1, n, out);
      for (auto& word : words) std::fill(word + n, word + padded, Word{0});
      gaussian_from_words(words[0], words[1], words[2], words[3], padded, values);
    } else {
      philox2x32_lanes(path, uniform_key, id_low + b, id_high + b, n, out);
      for (int k = 0; k < 2; ++k) std::fill(words[k] + n, words[k] + padded, Word{0});
      uniform_from_words(words[0], words[1], padded, values);
    }
    std::copy(values, values + n, theta + b);
  }
}

double pair_noise(const PairNoise& noise, std::int64_t id_a, std::int64_t id_b, std::int64_t step) {
  const auto low = static_cast<Word>(std::min(id_a, id_b));
  const auto high = static_cast<Word>(std::max(id_a, id_b));
  double theta = 0.0;
  pair_noise_batch(noise, &low, &high, step, 1, &theta);
  return theta;
}

void check_pair_noise_ids(const DpdParticles& particles) {
  constexpr std::int64_t kLimit = std::int64_t{1} << 32;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const std::int64_t id = particles.id[i];
    if (id < 0 || id >= kLimit) {
      throw Error("DPD noise: particle id " + std::to_string(id) +
                  " is outside [0, 2^32); the pair noise keys ids in 32 bits, so renumber "
                  "the particles (a LAMMPS data file may use any ids)");
    }
  }
}

}  // namespace pbms::dpd
