// Philox4x32-10 and Philox2x32-10 (Salmon, Moraes, Dror & Shaw 2011; the
// generators of Random123's philox.h) for many counters at once: one key,
// counters {c0[m], c1[m], c2, c3} (4x32) or {c0[m], c1[m]} (2x32). The DPD pair
// noise needs one draw per pair per step, and a scalar draw costs more than
// the conservative force of the pair; 8 (AVX-512) or 4 (AVX2) counters per
// register (philox_avx512.hpp) make it cheap. Integer arithmetic only, so every path returns
// the same bits, and a unit test holds each to Random123's own generator.
#pragma once

#include <cstdint>

namespace pbms::dpd {

enum class SimdPath { kPortable, kAvx2, kAvx512 };

// Whether this processor runs the path; kPortable always.
bool simd_path_supported(SimdPath path);
// The widest supported path, chosen once.
SimdPath fastest_simd_path();

// Output word k of counter m goes to out.word[k][m] (2x32: k < 2).
struct PhiloxLaneOutput {
  std::uint32_t* word[4];
};

void philox4x32_lanes(SimdPath path, const std::uint32_t key[2], const std::uint32_t* c0,
                      const std::uint32_t* c1, std::uint32_t c2, std::uint32_t c3, int count,
                      PhiloxLaneOutput out);

void philox2x32_lanes(SimdPath path, std::uint32_t key, const std::uint32_t* c0,
                      const std::uint32_t* c1, int count, PhiloxLaneOutput out);

}  // namespace pbms::dpd
