#include "kernels/philox4x32_lanes.hpp"

#include "kernels/philox4x32_avx512.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace pbms::dpd {

namespace {

using Word = std::uint32_t;
using Wide = std::uint64_t;

using philox::kMultiplier0;
using philox::kMultiplier1;
using philox::kRounds;
using philox::RoundKeys;

void lanes_portable(const Word key[2], const Word* low, const Word* high, Word step0, Word step1,
                    int count, PhiloxLaneOutput out) {
  const RoundKeys keys(key);
  for (int m = 0; m < count; ++m) {
    Word c0 = low[m], c1 = high[m], c2 = step0, c3 = step1;
    for (int round = 0; round < kRounds; ++round) {
      const Wide p0 = Wide{kMultiplier0} * c0;
      const Wide p1 = Wide{kMultiplier1} * c2;
      c0 = static_cast<Word>(p1 >> 32) ^ c1 ^ keys.k0[round];
      c1 = static_cast<Word>(p1);
      c2 = static_cast<Word>(p0 >> 32) ^ c3 ^ keys.k1[round];
      c3 = static_cast<Word>(p0);
    }
    out.word[0][m] = c0;
    out.word[1][m] = c1;
    out.word[2][m] = c2;
    out.word[3][m] = c3;
  }
}

// The vector paths keep one counter in each 64-bit lane (philox4x32_avx512.hpp).
__attribute__((target("avx512f"))) void lanes_avx512(const Word key[2], const Word* low,
                                                     const Word* high, Word step0, Word step1,
                                                     int count, PhiloxLaneOutput out) {
  const RoundKeys keys(key);
  for (int b = 0; b < count; b += 16) {
    const int left = count - b;
    const __mmask16 mask = left >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1u);
    const __m512i low16 = _mm512_maskz_loadu_epi32(mask, low + b);
    const __m512i high16 = _mm512_maskz_loadu_epi32(mask, high + b);
    philox::Counters8<2> x;
    x.c[0][0] = _mm512_cvtepu32_epi64(_mm512_castsi512_si256(low16));
    x.c[0][1] = _mm512_cvtepu32_epi64(_mm512_extracti64x4_epi64(low16, 1));
    x.c[1][0] = _mm512_cvtepu32_epi64(_mm512_castsi512_si256(high16));
    x.c[1][1] = _mm512_cvtepu32_epi64(_mm512_extracti64x4_epi64(high16, 1));
    philox::philox_avx512(keys, step0, step1, x);
    // vpmovqd keeps the low half of each lane: the words, in counter order.
    for (int k = 0; k < 4; ++k) {
      const __m512i both =
          _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvtepi64_epi32(x.c[k][0])),
                             _mm512_cvtepi64_epi32(x.c[k][1]), 1);
      _mm512_mask_storeu_epi32(out.word[k] + b, mask, both);
    }
  }
}

// The same layout with 4 counters per register and no three-way xor.
__attribute__((target("avx2"))) void lanes_avx2(const Word key[2], const Word* low,
                                                const Word* high, Word step0, Word step1, int count,
                                                PhiloxLaneOutput out) {
  const RoundKeys keys(key);
  const __m256i m0 = _mm256_set1_epi64x(kMultiplier0);
  const __m256i m1 = _mm256_set1_epi64x(kMultiplier1);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  // The even 32-bit elements hold the words after vpermd.
  const __m256i pack = _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0);
  for (int b = 0; b < count; b += 8) {
    const __m256i mask = _mm256_cmpgt_epi32(_mm256_set1_epi32(count - b), lane);
    const __m256i low8 = _mm256_maskload_epi32(reinterpret_cast<const int*>(low + b), mask);
    const __m256i high8 = _mm256_maskload_epi32(reinterpret_cast<const int*>(high + b), mask);
    __m256i a0 = _mm256_cvtepu32_epi64(_mm256_castsi256_si128(low8));
    __m256i b0 = _mm256_cvtepu32_epi64(_mm256_extracti128_si256(low8, 1));
    __m256i a1 = _mm256_cvtepu32_epi64(_mm256_castsi256_si128(high8));
    __m256i b1 = _mm256_cvtepu32_epi64(_mm256_extracti128_si256(high8, 1));
    __m256i a2 = _mm256_set1_epi64x(step0), b2 = a2;
    __m256i a3 = _mm256_set1_epi64x(step1), b3 = a3;
    for (int round = 0; round < kRounds; ++round) {
      const __m256i k0 = _mm256_set1_epi64x(keys.k0[round]);
      const __m256i k1 = _mm256_set1_epi64x(keys.k1[round]);
      const __m256i ap0 = _mm256_mul_epu32(a0, m0), bp0 = _mm256_mul_epu32(b0, m0);
      const __m256i ap1 = _mm256_mul_epu32(a2, m1), bp1 = _mm256_mul_epu32(b2, m1);
      a0 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(ap1, 32), a1), k0);
      b0 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(bp1, 32), b1), k0);
      a2 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(ap0, 32), a3), k1);
      b2 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(bp0, 32), b3), k1);
      a1 = ap1;
      b1 = bp1;
      a3 = ap0;
      b3 = bp0;
    }
    const auto store = [&](Word* to, __m256i first4, __m256i second4) {
      const __m256i words =
          _mm256_permute2x128_si256(_mm256_permutevar8x32_epi32(first4, pack),
                                    _mm256_permutevar8x32_epi32(second4, pack), 0x20);
      _mm256_maskstore_epi32(reinterpret_cast<int*>(to + b), mask, words);
    };
    store(out.word[0], a0, b0);
    store(out.word[1], a1, b1);
    store(out.word[2], a2, b2);
    store(out.word[3], a3, b3);
  }
}

}  // namespace

bool simd_path_supported(SimdPath path) {
  __builtin_cpu_init();
  switch (path) {
    case SimdPath::kAvx512:
      return __builtin_cpu_supports("avx512f") != 0;
    case SimdPath::kAvx2:
      return __builtin_cpu_supports("avx2") != 0;
    case SimdPath::kPortable:
      return true;
  }
  return false;
}

SimdPath fastest_simd_path() {
  static const SimdPath path = [] {
    if (simd_path_supported(SimdPath::kAvx512)) return SimdPath::kAvx512;
    if (simd_path_supported(SimdPath::kAvx2)) return SimdPath::kAvx2;
    return SimdPath::kPortable;
  }();
  return path;
}

void philox4x32_lanes(SimdPath path, const std::uint32_t key[2], const std::uint32_t* c0,
                      const std::uint32_t* c1, std::uint32_t c2, std::uint32_t c3, int count,
                      PhiloxLaneOutput out) {
  switch (path) {
    case SimdPath::kAvx512:
      lanes_avx512(key, c0, c1, c2, c3, count, out);
      return;
    case SimdPath::kAvx2:
      lanes_avx2(key, c0, c1, c2, c3, count, out);
      return;
    case SimdPath::kPortable:
      lanes_portable(key, c0, c1, c2, c3, count, out);
      return;
  }
}

}  // namespace pbms::dpd

#pragma GCC diagnostic pop
