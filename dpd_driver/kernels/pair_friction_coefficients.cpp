#include "kernels/pair_friction_coefficients.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/pair_noise.hpp"
#include "kernels/philox_avx512.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace pbms::dpd {

namespace {

constexpr int kChunk = 64;

void split_ids(const std::uint64_t* id_pair, int count, std::uint32_t* low, std::uint32_t* high) {
  for (int m = 0; m < count; ++m) {
    low[m] = static_cast<std::uint32_t>(id_pair[m]);
    high[m] = static_cast<std::uint32_t>(id_pair[m] >> 32);
  }
}

void coefficients_portable(const PairFrictionTerm& term, const std::uint64_t* id_pair,
                           const double* r2, const double* force_over_r, int count,
                           double* total_over_r, double* drag) {
  alignas(64) std::uint32_t low[kChunk], high[kChunk];
  alignas(64) double theta[kChunk];
  for (int c = 0; c < count; c += kChunk) {
    const int n = std::min(kChunk, count - c);
    split_ids(id_pair + c, n, low, high);
    pair_noise_batch(term.noise, low, high, term.step, n, theta);
    for (int m = 0; m < n; ++m) {
      const double s = 1.0 / std::sqrt(r2[c + m]);
      const double w_over_r = std::max(0.0, 1.0 - r2[c + m] * s * term.inverse_cutoff) * s;
      total_over_r[c + m] = force_over_r[c + m] + term.noise_factor * theta[m] * w_over_r;
      drag[c + m] = term.friction_factor * w_over_r * w_over_r;
    }
  }
}

__attribute__((target("avx512f,avx512dq"))) void coefficients_avx512(
    const PairFrictionTerm& term, const std::uint64_t* id_pair, const double* r2,
    const double* force_over_r, int count, double* total_over_r, double* drag) {
  // Groups of 8 pairs per pass: a Philox2x32 round is one chain of multiply,
  // shift and xor, so 8 independent chains keep the multiplier busy (2 groups
  // left the pass latency-bound).
  constexpr int kGroups = 8;
  const bool draw_here = term.noise.distribution == PairNoiseDistribution::kUniform;
  const philox::RoundKeys2x32 keys(term.noise.uniform_key(term.step));
  const __m512i low_half = _mm512_set1_epi64(0xffffffffLL);
  const __m512i exponent_one = _mm512_set1_epi64(0x3ff0000000000000LL);
  const __m512d one = _mm512_set1_pd(1.0);
  const __m512d half = _mm512_set1_pd(0.5);
  const __m512d three_halves = _mm512_set1_pd(1.5);
  const __m512d inverse_cutoff = _mm512_set1_pd(term.inverse_cutoff);
  const __m512d noise_factor = _mm512_set1_pd(term.noise_factor);
  const __m512d friction_factor = _mm512_set1_pd(term.friction_factor);

  alignas(64) std::uint32_t low[kChunk], high[kChunk];
  alignas(64) double theta[kChunk];
  for (int c = 0; c < count; c += kChunk) {
    const int n = std::min(kChunk, count - c);
    if (!draw_here) {
      split_ids(id_pair + c, n, low, high);
      pair_noise_batch(term.noise, low, high, term.step, n, theta);
    }
    for (int m = 0; m < n; m += 8 * kGroups) {
      __mmask8 mask[kGroups];
      for (int g = 0; g < kGroups; ++g) {
        const int left = std::clamp(n - m - 8 * g, 0, 8);
        mask[g] = static_cast<__mmask8>((1u << left) - 1u);
      }
      __m512d th[kGroups];
      if (draw_here) {
        __m512i x[2][kGroups];
        for (int g = 0; g < kGroups; ++g) {
          // The counter's two words are the low and high halves; the upper
          // half of lane word 0 is ignored by Philox's multiply.
          const __m512i ids = _mm512_maskz_loadu_epi64(mask[g], id_pair + (c + m + 8 * g));
          x[0][g] = ids;
          x[1][g] = _mm512_srli_epi64(ids, 32);
        }
        philox::philox2x32_avx512(keys, x);
        for (int g = 0; g < kGroups; ++g) {
          // θ = √3 (2u − 1), u = (k + ½) 2^-52 for the top 52 bits k of
          // words 1:0, in the operations of pair_noise.cpp (same bits).
          const __m512i bits =
              _mm512_or_si512(_mm512_slli_epi64(x[1][g], 32), _mm512_and_si512(x[0][g], low_half));
          const __m512d mantissa =
              _mm512_castsi512_pd(_mm512_or_si512(_mm512_srli_epi64(bits, 12), exponent_one));
          const __m512d u = _mm512_add_pd(_mm512_sub_pd(mantissa, one), _mm512_set1_pd(0x1p-53));
          th[g] = _mm512_mul_pd(_mm512_set1_pd(1.7320508075688772),
                                _mm512_sub_pd(_mm512_mul_pd(_mm512_set1_pd(2.0), u), one));
        }
      } else {
        for (int g = 0; g < kGroups; ++g) {
          th[g] = _mm512_maskz_loadu_pd(mask[g], theta + (m + 8 * g));
        }
      }
      for (int g = 0; g < kGroups; ++g) {
        const int at = c + m + 8 * g;
        // Lanes past the end read r² = 1, so that none divides by zero.
        const __m512d d2 = _mm512_mask_loadu_pd(one, mask[g], r2 + at);
        const __m512d half_d2 = _mm512_mul_pd(half, d2);
        __m512d s = _mm512_rsqrt14_pd(d2);
        s = _mm512_mul_pd(s, _mm512_fnmadd_pd(half_d2, _mm512_mul_pd(s, s), three_halves));
        s = _mm512_mul_pd(s, _mm512_fnmadd_pd(half_d2, _mm512_mul_pd(s, s), three_halves));
        const __m512d w = _mm512_max_pd(
            _mm512_setzero_pd(), _mm512_fnmadd_pd(_mm512_mul_pd(d2, s), inverse_cutoff, one));
        const __m512d w_over_r = _mm512_mul_pd(w, s);
        const __m512d conservative = _mm512_maskz_loadu_pd(mask[g], force_over_r + at);
        _mm512_mask_storeu_pd(
            total_over_r + at, mask[g],
            _mm512_fmadd_pd(_mm512_mul_pd(noise_factor, th[g]), w_over_r, conservative));
        _mm512_mask_storeu_pd(drag + at, mask[g],
                              _mm512_mul_pd(_mm512_mul_pd(friction_factor, w_over_r), w_over_r));
      }
    }
  }
}

}  // namespace

void pair_friction_coefficients(const PairFrictionTerm& term, const std::uint64_t* id_pair,
                                const double* r2, const double* force_over_r, int count,
                                double* total_over_r, double* drag) {
  pair_friction_coefficients(fastest_simd_path(), term, id_pair, r2, force_over_r, count,
                             total_over_r, drag);
}

void pair_friction_coefficients(SimdPath path, const PairFrictionTerm& term,
                                const std::uint64_t* id_pair, const double* r2,
                                const double* force_over_r, int count, double* total_over_r,
                                double* drag) {
  // fastest_simd_path() asks the processor once; this runs once per batch.
  if (path == SimdPath::kAvx512 && fastest_simd_path() == SimdPath::kAvx512) {
    coefficients_avx512(term, id_pair, r2, force_over_r, count, total_over_r, drag);
  } else {
    coefficients_portable(term, id_pair, r2, force_over_r, count, total_over_r, drag);
  }
}

}  // namespace pbms::dpd

#pragma GCC diagnostic pop
