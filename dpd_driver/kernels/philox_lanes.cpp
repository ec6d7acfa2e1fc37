#include "kernels/philox_lanes.hpp"

#include "kernels/philox_avx512.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace pbms::dpd {

namespace {

using Word = std::uint32_t;
using Wide = std::uint64_t;

using philox::kMultiplier0;
using philox::kMultiplier1;
using philox::kMultiplier2x32;
using philox::kRounds;
using philox::RoundKeys;
using philox::RoundKeys2x32;

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

// The vector paths keep one counter in each 64-bit lane (philox_avx512.hpp):
// 16 words of a counter field widen into two AVX-512 registers (8 into two
// AVX2 ones), and the low halves of the lanes narrow back into words in
// counter order (vpmovqd, vpermd).
// The first min(left, 16) lanes.
inline __mmask16 lane_mask16(int left) {
  return left >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1u);
}

[[gnu::always_inline, gnu::target("avx512f")]] inline void widen16(__mmask16 mask,
                                                                   const Word* words,
                                                                   __m512i (&lanes)[2]) {
  const __m512i w = _mm512_maskz_loadu_epi32(mask, words);
  lanes[0] = _mm512_cvtepu32_epi64(_mm512_castsi512_si256(w));
  lanes[1] = _mm512_cvtepu32_epi64(_mm512_extracti64x4_epi64(w, 1));
}

[[gnu::always_inline, gnu::target("avx512f")]] inline void narrow16(__mmask16 mask,
                                                                    const __m512i (&lanes)[2],
                                                                    Word* words) {
  const __m512i both = _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvtepi64_epi32(lanes[0])),
                                          _mm512_cvtepi64_epi32(lanes[1]), 1);
  _mm512_mask_storeu_epi32(words, mask, both);
}

[[gnu::always_inline, gnu::target("avx2")]] inline __m256i lane_mask8(int left) {
  return _mm256_cmpgt_epi32(_mm256_set1_epi32(left), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
}

[[gnu::always_inline, gnu::target("avx2")]] inline void widen8(__m256i mask, const Word* words,
                                                               __m256i& first, __m256i& second) {
  const __m256i w = _mm256_maskload_epi32(reinterpret_cast<const int*>(words), mask);
  first = _mm256_cvtepu32_epi64(_mm256_castsi256_si128(w));
  second = _mm256_cvtepu32_epi64(_mm256_extracti128_si256(w, 1));
}

[[gnu::always_inline, gnu::target("avx2")]] inline void narrow8(__m256i mask, __m256i first,
                                                                __m256i second, Word* words) {
  // The even 32-bit elements hold the words after vpermd.
  const __m256i pack = _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0);
  const __m256i packed = _mm256_permute2x128_si256(_mm256_permutevar8x32_epi32(first, pack),
                                                   _mm256_permutevar8x32_epi32(second, pack), 0x20);
  _mm256_maskstore_epi32(reinterpret_cast<int*>(words), mask, packed);
}

__attribute__((target("avx512f"))) void lanes_avx512(const Word key[2], const Word* low,
                                                     const Word* high, Word step0, Word step1,
                                                     int count, PhiloxLaneOutput out) {
  const RoundKeys keys(key);
  for (int b = 0; b < count; b += 16) {
    const __mmask16 mask = lane_mask16(count - b);
    philox::Counters8<2> x;
    widen16(mask, low + b, x.c[0]);
    widen16(mask, high + b, x.c[1]);
    philox::philox_avx512(keys, step0, step1, x);
    for (int k = 0; k < 4; ++k) narrow16(mask, x.c[k], out.word[k] + b);
  }
}

// The same layout with 4 counters per register and no three-way xor.
__attribute__((target("avx2"))) void lanes_avx2(const Word key[2], const Word* low,
                                                const Word* high, Word step0, Word step1, int count,
                                                PhiloxLaneOutput out) {
  const RoundKeys keys(key);
  const __m256i m0 = _mm256_set1_epi64x(kMultiplier0);
  const __m256i m1 = _mm256_set1_epi64x(kMultiplier1);
  for (int b = 0; b < count; b += 8) {
    const __m256i mask = lane_mask8(count - b);
    __m256i a0, b0, a1, b1;
    widen8(mask, low + b, a0, b0);
    widen8(mask, high + b, a1, b1);
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
    narrow8(mask, a0, b0, out.word[0] + b);
    narrow8(mask, a1, b1, out.word[1] + b);
    narrow8(mask, a2, b2, out.word[2] + b);
    narrow8(mask, a3, b3, out.word[3] + b);
  }
}

void lanes2x32_portable(Word key, const Word* low, const Word* high, int count,
                        PhiloxLaneOutput out) {
  const RoundKeys2x32 keys(key);
  for (int m = 0; m < count; ++m) {
    Word c0 = low[m], c1 = high[m];
    for (int round = 0; round < kRounds; ++round) {
      const Wide p = Wide{kMultiplier2x32} * c0;
      c0 = static_cast<Word>(p >> 32) ^ c1 ^ keys.k[round];
      c1 = static_cast<Word>(p);
    }
    out.word[0][m] = c0;
    out.word[1][m] = c1;
  }
}

__attribute__((target("avx512f"))) void lanes2x32_avx512(Word key, const Word* low,
                                                         const Word* high, int count,
                                                         PhiloxLaneOutput out) {
  const RoundKeys2x32 keys(key);
  for (int b = 0; b < count; b += 16) {
    const __mmask16 mask = lane_mask16(count - b);
    __m512i c[2][2];
    widen16(mask, low + b, c[0]);
    widen16(mask, high + b, c[1]);
    philox::philox2x32_avx512(keys, c);
    for (int k = 0; k < 2; ++k) narrow16(mask, c[k], out.word[k] + b);
  }
}

__attribute__((target("avx2"))) void lanes2x32_avx2(Word key, const Word* low, const Word* high,
                                                    int count, PhiloxLaneOutput out) {
  const RoundKeys2x32 keys(key);
  const __m256i m = _mm256_set1_epi64x(kMultiplier2x32);
  for (int b = 0; b < count; b += 8) {
    const __m256i mask = lane_mask8(count - b);
    __m256i a0, b0, a1, b1;
    widen8(mask, low + b, a0, b0);
    widen8(mask, high + b, a1, b1);
    for (int round = 0; round < kRounds; ++round) {
      const __m256i k = _mm256_set1_epi64x(keys.k[round]);
      const __m256i ap = _mm256_mul_epu32(a0, m), bp = _mm256_mul_epu32(b0, m);
      a0 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(ap, 32), a1), k);
      b0 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(bp, 32), b1), k);
      a1 = ap;
      b1 = bp;
    }
    narrow8(mask, a0, b0, out.word[0] + b);
    narrow8(mask, a1, b1, out.word[1] + b);
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

void philox2x32_lanes(SimdPath path, std::uint32_t key, const std::uint32_t* c0,
                      const std::uint32_t* c1, int count, PhiloxLaneOutput out) {
  switch (path) {
    case SimdPath::kAvx512:
      lanes2x32_avx512(key, c0, c1, count, out);
      return;
    case SimdPath::kAvx2:
      lanes2x32_avx2(key, c0, c1, count, out);
      return;
    case SimdPath::kPortable:
      lanes2x32_portable(key, c0, c1, count, out);
      return;
  }
}

}  // namespace pbms::dpd

#pragma GCC diagnostic pop
