// Philox4x32-10 and Philox2x32-10 on 8 counters in AVX-512 registers, one
// counter per 64-bit lane with its word in the low half: vpmuludq multiplies
// exactly those halves into the full 64-bit product, a 32-bit shift brings
// its high word down, and its low word stays where the next round reads it.
// The upper halves carry leftovers that no multiply reads; whoever uses a
// word takes its low 32 bits. A round for 8 counters is two multiplies, two
// shifts and two three-way xors (4x32) or one of each (2x32), with no blends
// to restore 32-bit lane order.
//
// Shared by the lane generators (philox_lanes.cpp) and the fused DPD
// friction kernel, which keeps Philox2x32's words in registers. Only for
// code built with (or inside a function targeted at) AVX-512F.
#pragma once

#include <cstdint>

// GCC 12's AVX-512 headers start some intrinsics from an undefined vector
// and then warn about it at -O3; nothing of ours is uninitialised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop

namespace pbms::dpd::philox {

// Salmon et al. 2011, as in Random123's philox.h.
inline constexpr std::uint32_t kMultiplier2x32 = 0xD256D193u;
inline constexpr std::uint32_t kMultiplier0 = 0xD2511F53u;
inline constexpr std::uint32_t kMultiplier1 = 0xCD9E8D57u;
inline constexpr std::uint32_t kWeyl0 = 0x9E3779B9u;
inline constexpr std::uint32_t kWeyl1 = 0xBB67AE85u;
inline constexpr int kRounds = 10;

// The round keys k + r·Weyl: the same for every lane, computed once.
struct RoundKeys {
  explicit RoundKeys(const std::uint32_t key[2]) {
    for (int round = 0; round < kRounds; ++round) {
      k0[round] = key[0] + static_cast<std::uint32_t>(round) * kWeyl0;
      k1[round] = key[1] + static_cast<std::uint32_t>(round) * kWeyl1;
    }
  }
  std::uint32_t k0[kRounds];
  std::uint32_t k1[kRounds];
};

// Philox2x32's round keys k + r·Weyl0.
struct RoundKeys2x32 {
  explicit RoundKeys2x32(std::uint32_t key) {
    for (int round = 0; round < kRounds; ++round) {
      k[round] = key + static_cast<std::uint32_t>(round) * kWeyl0;
    }
  }
  std::uint32_t k[kRounds];
};

// Four words of G counters (G independent groups of 8, so that one group's
// multiplies overlap another's dependent shifts and xors).
template <int G>
struct Counters8 {
  __m512i c[4][G];
};

// Philox4x32-10 of the counters {c0, c1, step0, step1}: words 0 and 1 differ
// by lane, words 2 and 3 (the step) are the same in every lane, so the first
// round's second product is one scalar multiply. On return x holds the
// output words.
template <int G>
[[gnu::always_inline, gnu::target("avx512f")]] inline void philox_avx512(const RoundKeys& keys,
                                                                         std::uint32_t step0,
                                                                         std::uint32_t step1,
                                                                         Counters8<G>& x) {
  const __m512i m0 = _mm512_set1_epi64(kMultiplier0);
  const __m512i m1 = _mm512_set1_epi64(kMultiplier1);
  {
    const std::uint64_t p1 = std::uint64_t{kMultiplier1} * step0;
    const __m512i word0_mask = _mm512_set1_epi64(static_cast<std::uint32_t>(p1 >> 32) ^ keys.k0[0]);
    const __m512i word1 = _mm512_set1_epi64(static_cast<std::uint32_t>(p1));
    const __m512i word2_mask = _mm512_set1_epi64(step1 ^ keys.k1[0]);
    for (int g = 0; g < G; ++g) {
      const __m512i p0 = _mm512_mul_epu32(x.c[0][g], m0);
      x.c[0][g] = _mm512_xor_si512(x.c[1][g], word0_mask);
      x.c[1][g] = word1;
      x.c[2][g] = _mm512_xor_si512(_mm512_srli_epi64(p0, 32), word2_mask);
      x.c[3][g] = p0;
    }
  }
  for (int round = 1; round < kRounds; ++round) {
    const __m512i k0 = _mm512_set1_epi64(keys.k0[round]);
    const __m512i k1 = _mm512_set1_epi64(keys.k1[round]);
    for (int g = 0; g < G; ++g) {
      const __m512i p1 = _mm512_mul_epu32(x.c[2][g], m1);
      const __m512i p0 = _mm512_mul_epu32(x.c[0][g], m0);
      x.c[2][g] = _mm512_ternarylogic_epi64(_mm512_srli_epi64(p0, 32), x.c[3][g], k1, 0x96);
      x.c[3][g] = p0;
      x.c[0][g] = _mm512_ternarylogic_epi64(_mm512_srli_epi64(p1, 32), x.c[1][g], k0, 0x96);
      x.c[1][g] = p1;
    }
  }
}

// Philox2x32-10 of G groups of 8 counters {c[0], c[1]}; on return they hold
// the output words.
template <int G>
[[gnu::always_inline, gnu::target("avx512f")]] inline void philox2x32_avx512(
    const RoundKeys2x32& keys, __m512i (&c)[2][G]) {
  const __m512i m = _mm512_set1_epi64(kMultiplier2x32);
  for (int round = 0; round < kRounds; ++round) {
    const __m512i k = _mm512_set1_epi64(keys.k[round]);
    for (int g = 0; g < G; ++g) {
      const __m512i p = _mm512_mul_epu32(c[0][g], m);
      c[0][g] = _mm512_ternarylogic_epi64(_mm512_srli_epi64(p, 32), c[1][g], k, 0x96);
      c[1][g] = p;
    }
  }
}

}  // namespace pbms::dpd::philox
