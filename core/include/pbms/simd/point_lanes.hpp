// Vectors of W doubles (and of W indices) for kernels that run one item per
// SIMD lane: W material points at once. kPointLanes is the width that fills
// one register of the instruction set the build targets (PBMS_ARCH): 8 with
// AVX-512, 4 with AVX2, 2 with SSE2. A wider vector would be split by the
// compiler into several registers and its lane shuffles into scalar moves
// through memory, which on AVX2 made the MPM grid step three times slower
// than on AVX-512 (issue 35).
#pragma once

#include <cstdint>

namespace pbms::simd {

template <int W>
struct LaneVectors;
template <>
struct LaneVectors<2> {
  using Real = double __attribute__((vector_size(16), may_alias));
  using Unaligned = double __attribute__((vector_size(16), aligned(8), may_alias));
  using Index = std::int64_t __attribute__((vector_size(16)));
  using Int32 = std::int32_t __attribute__((vector_size(8)));
};
template <>
struct LaneVectors<4> {
  using Real = double __attribute__((vector_size(32), may_alias));
  using Unaligned = double __attribute__((vector_size(32), aligned(8), may_alias));
  using Index = std::int64_t __attribute__((vector_size(32)));
  using Int32 = std::int32_t __attribute__((vector_size(16)));
};
template <>
struct LaneVectors<8> {
  using Real = double __attribute__((vector_size(64), may_alias));
  using Unaligned = double __attribute__((vector_size(64), aligned(8), may_alias));
  using Index = std::int64_t __attribute__((vector_size(64)));
  using Int32 = std::int32_t __attribute__((vector_size(32)));
};

// W doubles, W signed 64-bit integers (the result of a lane comparison,
// node indices), W 32-bit integers (conversions from doubles, which AVX2
// and SSE2 do only to 32 bits).
// A plain alias template with a dependent vector_size loses the attribute
// in GCC 12, hence the specialisations above.
template <int W>
using Lanes = typename LaneVectors<W>::Real;
template <int W>
using IndexLanes = typename LaneVectors<W>::Index;
template <int W>
using Int32Lanes = typename LaneVectors<W>::Int32;

// W doubles from p and to p, which need only a double's alignment. One
// vector load or store each: copied through memcpy in a loop, GCC 12 moved
// them in 16-byte pieces through the stack, and the wider reload that
// followed waited on a failed store forwarding (a third of the AVX2
// velocity-gradient pass).
template <int W>
[[gnu::always_inline]] inline Lanes<W> load_lanes(const double* p) {
  return *reinterpret_cast<const typename LaneVectors<W>::Unaligned*>(p);
}
template <int W>
[[gnu::always_inline]] inline void store_lanes(double* p, Lanes<W> v) {
  *reinterpret_cast<typename LaneVectors<W>::Unaligned*>(p) = v;
}

// Whether every lane of a comparison's result is true, by halving the
// vector until one lane is left (shuffles, no branch per lane).
template <int W>
[[gnu::always_inline]] inline bool all_lanes_set(IndexLanes<W> m) {
  if constexpr (W == 8) {
    m &= __builtin_shufflevector(m, m, 4, 5, 6, 7, 0, 1, 2, 3);
    m &= __builtin_shufflevector(m, m, 2, 3, 0, 1, 2, 3, 0, 1);
    m &= __builtin_shufflevector(m, m, 1, 0, 1, 0, 1, 0, 1, 0);
  } else if constexpr (W == 4) {
    m &= __builtin_shufflevector(m, m, 2, 3, 0, 1);
    m &= __builtin_shufflevector(m, m, 1, 0, 1, 0);
  } else {
    static_assert(W == 2);
    m &= __builtin_shufflevector(m, m, 1, 0);
  }
  return m[0] != 0;
}

#if defined(__AVX512F__)
inline constexpr int kPointLanes = 8;
#elif defined(__AVX__)
inline constexpr int kPointLanes = 4;
#else
inline constexpr int kPointLanes = 2;
#endif

// The instruction set this translation unit was compiled for, for tests and
// benches that say which width they ran.
inline constexpr const char* kPointLanesIsa = kPointLanes == 8   ? "AVX-512"
                                              : kPointLanes == 4 ? "AVX2"
                                                                 : "SSE2";

}  // namespace pbms::simd
