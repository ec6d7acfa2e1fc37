#include "kernels/philox4x32_lanes.hpp"

// GCC 12's AVX-512 headers start some intrinsics from an undefined vector
// and then warn about it at -O3; nothing of ours is uninitialised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

namespace pbms::dpd {

namespace {

using Word = std::uint32_t;
using Wide = std::uint64_t;

// Philox4x32 constants (Salmon et al. 2011, as in Random123's philox.h).
constexpr Word kMultiplier0 = 0xD2511F53u;
constexpr Word kMultiplier1 = 0xCD9E8D57u;
constexpr Word kWeyl0 = 0x9E3779B9u;
constexpr Word kWeyl1 = 0xBB67AE85u;
constexpr int kRounds = 10;

void lanes_portable(const Word key[2], const Word* low, const Word* high, Word step0, Word step1,
                    int count, PhiloxLaneOutput out) {
  for (int m = 0; m < count; ++m) {
    Word c0 = low[m], c1 = high[m], c2 = step0, c3 = step1;
    Word k0 = key[0], k1 = key[1];
    for (int round = 0; round < kRounds; ++round) {
      const Wide p0 = Wide{kMultiplier0} * c0;
      const Wide p1 = Wide{kMultiplier1} * c2;
      c0 = static_cast<Word>(p1 >> 32) ^ c1 ^ k0;
      c1 = static_cast<Word>(p1);
      c2 = static_cast<Word>(p0 >> 32) ^ c3 ^ k1;
      c3 = static_cast<Word>(p0);
      k0 += kWeyl0;
      k1 += kWeyl1;
    }
    out.word[0][m] = c0;
    out.word[1][m] = c1;
    out.word[2][m] = c2;
    out.word[3][m] = c3;
  }
}

// The 32 × 32 → 64 products of even and odd lanes come from two
// vpmuludq; the blends put high and low halves back in lane order.
__attribute__((target("avx512f"))) void lanes_avx512(const Word key[2], const Word* low,
                                                     const Word* high, Word step0, Word step1,
                                                     int count, PhiloxLaneOutput out) {
  const __m512i m0 = _mm512_set1_epi64(kMultiplier0);
  const __m512i m1 = _mm512_set1_epi64(kMultiplier1);
  constexpr __mmask16 kOdd = 0xAAAA;
  for (int b = 0; b < count; b += 16) {
    const int left = count - b;
    const __mmask16 mask = left >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1u);
    __m512i c0 = _mm512_maskz_loadu_epi32(mask, low + b);
    __m512i c1 = _mm512_maskz_loadu_epi32(mask, high + b);
    __m512i c2 = _mm512_set1_epi32(static_cast<int>(step0));
    __m512i c3 = _mm512_set1_epi32(static_cast<int>(step1));
    __m512i k0 = _mm512_set1_epi32(static_cast<int>(key[0]));
    __m512i k1 = _mm512_set1_epi32(static_cast<int>(key[1]));
    const __m512i weyl0 = _mm512_set1_epi32(static_cast<int>(kWeyl0));
    const __m512i weyl1 = _mm512_set1_epi32(static_cast<int>(kWeyl1));
    for (int round = 0; round < kRounds; ++round) {
      const __m512i even0 = _mm512_mul_epu32(c0, m0);
      const __m512i odd0 = _mm512_mul_epu32(_mm512_srli_epi64(c0, 32), m0);
      const __m512i even1 = _mm512_mul_epu32(c2, m1);
      const __m512i odd1 = _mm512_mul_epu32(_mm512_srli_epi64(c2, 32), m1);
      const __m512i hi0 = _mm512_mask_blend_epi32(kOdd, _mm512_srli_epi64(even0, 32), odd0);
      const __m512i lo0 = _mm512_mask_blend_epi32(kOdd, even0, _mm512_slli_epi64(odd0, 32));
      const __m512i hi1 = _mm512_mask_blend_epi32(kOdd, _mm512_srli_epi64(even1, 32), odd1);
      const __m512i lo1 = _mm512_mask_blend_epi32(kOdd, even1, _mm512_slli_epi64(odd1, 32));
      c0 = _mm512_ternarylogic_epi32(hi1, c1, k0, 0x96);  // three-way xor
      c1 = lo1;
      c2 = _mm512_ternarylogic_epi32(hi0, c3, k1, 0x96);
      c3 = lo0;
      k0 = _mm512_add_epi32(k0, weyl0);
      k1 = _mm512_add_epi32(k1, weyl1);
    }
    _mm512_mask_storeu_epi32(out.word[0] + b, mask, c0);
    _mm512_mask_storeu_epi32(out.word[1] + b, mask, c1);
    _mm512_mask_storeu_epi32(out.word[2] + b, mask, c2);
    _mm512_mask_storeu_epi32(out.word[3] + b, mask, c3);
  }
}

__attribute__((target("avx2"))) void lanes_avx2(const Word key[2], const Word* low,
                                                const Word* high, Word step0, Word step1, int count,
                                                PhiloxLaneOutput out) {
  const __m256i m0 = _mm256_set1_epi64x(kMultiplier0);
  const __m256i m1 = _mm256_set1_epi64x(kMultiplier1);
  const __m256i weyl0 = _mm256_set1_epi32(static_cast<int>(kWeyl0));
  const __m256i weyl1 = _mm256_set1_epi32(static_cast<int>(kWeyl1));
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (int b = 0; b < count; b += 8) {
    const __m256i mask = _mm256_cmpgt_epi32(_mm256_set1_epi32(count - b), lane);
    __m256i c0 = _mm256_maskload_epi32(reinterpret_cast<const int*>(low + b), mask);
    __m256i c1 = _mm256_maskload_epi32(reinterpret_cast<const int*>(high + b), mask);
    __m256i c2 = _mm256_set1_epi32(static_cast<int>(step0));
    __m256i c3 = _mm256_set1_epi32(static_cast<int>(step1));
    __m256i k0 = _mm256_set1_epi32(static_cast<int>(key[0]));
    __m256i k1 = _mm256_set1_epi32(static_cast<int>(key[1]));
    for (int round = 0; round < kRounds; ++round) {
      const __m256i even0 = _mm256_mul_epu32(c0, m0);
      const __m256i odd0 = _mm256_mul_epu32(_mm256_srli_epi64(c0, 32), m0);
      const __m256i even1 = _mm256_mul_epu32(c2, m1);
      const __m256i odd1 = _mm256_mul_epu32(_mm256_srli_epi64(c2, 32), m1);
      const __m256i hi0 = _mm256_blend_epi32(_mm256_srli_epi64(even0, 32), odd0, 0xAA);
      const __m256i lo0 = _mm256_blend_epi32(even0, _mm256_slli_epi64(odd0, 32), 0xAA);
      const __m256i hi1 = _mm256_blend_epi32(_mm256_srli_epi64(even1, 32), odd1, 0xAA);
      const __m256i lo1 = _mm256_blend_epi32(even1, _mm256_slli_epi64(odd1, 32), 0xAA);
      c0 = _mm256_xor_si256(_mm256_xor_si256(hi1, c1), k0);
      c1 = lo1;
      c2 = _mm256_xor_si256(_mm256_xor_si256(hi0, c3), k1);
      c3 = lo0;
      k0 = _mm256_add_epi32(k0, weyl0);
      k1 = _mm256_add_epi32(k1, weyl1);
    }
    _mm256_maskstore_epi32(reinterpret_cast<int*>(out.word[0] + b), mask, c0);
    _mm256_maskstore_epi32(reinterpret_cast<int*>(out.word[1] + b), mask, c1);
    _mm256_maskstore_epi32(reinterpret_cast<int*>(out.word[2] + b), mask, c2);
    _mm256_maskstore_epi32(reinterpret_cast<int*>(out.word[3] + b), mask, c3);
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
