// Layout changes between records and lanes for kernels that run one item
// per SIMD lane (W material points at once, simd/point_lanes.hpp): a W x W
// transpose, records of F doubles stored one after another as one lane
// vector per field and back, and eight-double records (a node's sums, one
// cache line) to and from lane vectors. Shuffles and moves only, so values
// are moved, never rounded. Every function is written for W = 2, 4 and 8
// with shuffles of W-wide vectors, which each instruction set does in
// registers.
#pragma once

#include <array>
#include <cstddef>

#include "pbms/simd/lanes8.hpp"
#include "pbms/simd/point_lanes.hpp"

namespace pbms::simd {

// r[i][j] becomes r[j][i].
template <int W>
[[gnu::always_inline]] inline void transpose(Lanes<W> (&r)[W]) {
  if constexpr (W == 2) {
    const Lanes<2> a = __builtin_shufflevector(r[0], r[1], 0, 2);
    r[1] = __builtin_shufflevector(r[0], r[1], 1, 3);
    r[0] = a;
  } else if constexpr (W == 4) {
    // Pairs within 128-bit halves, then halves across registers.
    const Lanes<4> t0 = __builtin_shufflevector(r[0], r[1], 0, 4, 2, 6);
    const Lanes<4> t1 = __builtin_shufflevector(r[0], r[1], 1, 5, 3, 7);
    const Lanes<4> t2 = __builtin_shufflevector(r[2], r[3], 0, 4, 2, 6);
    const Lanes<4> t3 = __builtin_shufflevector(r[2], r[3], 1, 5, 3, 7);
    r[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
    r[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    r[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
    r[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
  } else {
    static_assert(W == 8);
    // Three rounds of two-register shuffles.
    Lanes<8> t[8];
    for (int i = 0; i < 8; i += 2) {
      t[i] = __builtin_shufflevector(r[i], r[i + 1], 0, 8, 2, 10, 4, 12, 6, 14);
      t[i + 1] = __builtin_shufflevector(r[i], r[i + 1], 1, 9, 3, 11, 5, 13, 7, 15);
    }
    for (int i = 0; i < 8; i += 4) {
      for (int j = 0; j < 2; ++j) {
        r[i + j] = __builtin_shufflevector(t[i + j], t[i + j + 2], 0, 1, 8, 9, 4, 5, 12, 13);
        r[i + j + 2] = __builtin_shufflevector(t[i + j], t[i + j + 2], 2, 3, 10, 11, 6, 7, 14, 15);
      }
    }
    for (int j = 0; j < 4; ++j) {
      t[j] = __builtin_shufflevector(r[j], r[j + 4], 0, 1, 2, 3, 8, 9, 10, 11);
      t[j + 4] = __builtin_shufflevector(r[j], r[j + 4], 4, 5, 6, 7, 12, 13, 14, 15);
    }
    for (int i = 0; i < 8; ++i) r[i] = t[i];
  }
}

// W records of F doubles at base (record k at base + F k) as one lane
// vector per field: c[f][k] = base[F k + f]. Whole W x W blocks of fields
// go through transposes; the fields after the last whole block lane by lane.
template <int W, int F>
[[gnu::always_inline]] inline void load_records(const double* base, Lanes<W> (&c)[F]) {
  constexpr int whole = F - F % W;
#pragma GCC unroll 8
  for (int f0 = 0; f0 < whole; f0 += W) {
    Lanes<W> r[W];
#pragma GCC unroll 8
    for (std::ptrdiff_t k = 0; k < W; ++k) r[k] = load_lanes<W>(base + F * k + f0);
    transpose<W>(r);
    for (int j = 0; j < W; ++j) c[f0 + j] = r[j];
  }
  for (int f = whole; f < F; ++f) {
    Lanes<W> lane{};
    for (int k = 0; k < W; ++k) lane[k] = base[F * k + f];
    c[f] = lane;
  }
}

// The inverse of load_records: writes the W F doubles at base.
template <int W, int F>
[[gnu::always_inline]] inline void store_records(const Lanes<W> (&c)[F], double* base) {
  constexpr int whole = F - F % W;
#pragma GCC unroll 8
  for (int f0 = 0; f0 < whole; f0 += W) {
    Lanes<W> r[W];
    for (int j = 0; j < W; ++j) r[j] = c[f0 + j];
    transpose<W>(r);
#pragma GCC unroll 8
    for (std::ptrdiff_t k = 0; k < W; ++k) store_lanes<W>(base + F * k + f0, r[k]);
  }
  for (int f = whole; f < F; ++f) {
    for (int k = 0; k < W; ++k) base[F * k + f] = c[f][k];
  }
}

// W 3-vectors at v (x y z x y z ...) as one lane vector per component:
// c[d][k] = v[k][d].
template <int W>
[[gnu::always_inline]] inline void deinterleave3(const std::array<double, 3>* v, Lanes<W> (&c)[3]) {
  // The 3 W doubles, W at a time.
  const Lanes<W> a = load_lanes<W>(v[0].data());
  const Lanes<W> b = load_lanes<W>(v[0].data() + W);
  const Lanes<W> e = load_lanes<W>(v[0].data() + std::ptrdiff_t{2} * W);
  if constexpr (W == 2) {
    // a = x0 y0, b = z0 x1, e = y1 z1.
    c[0] = __builtin_shufflevector(a, b, 0, 3);
    c[1] = __builtin_shufflevector(a, e, 1, 2);
    c[2] = __builtin_shufflevector(b, e, 0, 3);
  } else if constexpr (W == 4) {
    // a = x0 y0 z0 x1, b = y1 z1 x2 y2, e = z2 x3 y3 z3.
    const Lanes<4> x = __builtin_shufflevector(a, b, 0, 3, 6, -1);
    const Lanes<4> y = __builtin_shufflevector(a, b, 1, 4, 7, -1);
    const Lanes<4> z = __builtin_shufflevector(a, b, 2, 5, -1, -1);
    c[0] = __builtin_shufflevector(x, e, 0, 1, 2, 5);
    c[1] = __builtin_shufflevector(y, e, 0, 1, 2, 6);
    c[2] = __builtin_shufflevector(z, e, 0, 1, 4, 7);
  } else {
    static_assert(W == 8);
    // a = x0 y0 z0 x1 y1 z1 x2 y2, b = z2 x3 y3 z3 x4 y4 z4 x5,
    // e = y5 z5 x6 y6 z6 x7 y7 z7.
    const Lanes<8> x = __builtin_shufflevector(a, b, 0, 3, 6, 9, 12, 15, 0, 0);
    const Lanes<8> y = __builtin_shufflevector(a, b, 1, 4, 7, 10, 13, 0, 0, 0);
    const Lanes<8> z = __builtin_shufflevector(a, b, 2, 5, 8, 11, 14, 0, 0, 0);
    c[0] = __builtin_shufflevector(x, e, 0, 1, 2, 3, 4, 5, 10, 13);
    c[1] = __builtin_shufflevector(y, e, 0, 1, 2, 3, 4, 8, 11, 14);
    c[2] = __builtin_shufflevector(z, e, 0, 1, 2, 3, 4, 9, 12, 15);
  }
}

// The inverse of deinterleave3: writes the 3 W doubles at v.
template <int W>
[[gnu::always_inline]] inline void interleave3(const Lanes<W> (&c)[3], std::array<double, 3>* v) {
  Lanes<W> a, b, e;
  if constexpr (W == 2) {
    a = __builtin_shufflevector(c[0], c[1], 0, 2);
    b = __builtin_shufflevector(c[2], c[0], 0, 3);
    e = __builtin_shufflevector(c[1], c[2], 1, 3);
  } else if constexpr (W == 4) {
    // a = x0 y0 z0 x1, b = y1 z1 x2 y2, e = z2 x3 y3 z3.
    const Lanes<4> xy_a = __builtin_shufflevector(c[0], c[1], 0, 4, -1, 1);
    a = __builtin_shufflevector(xy_a, c[2], 0, 1, 4, 3);
    const Lanes<4> xy_b = __builtin_shufflevector(c[0], c[1], 5, -1, 2, 6);
    b = __builtin_shufflevector(xy_b, c[2], 0, 5, 2, 3);
    const Lanes<4> xy_e = __builtin_shufflevector(c[0], c[1], -1, 3, 7, -1);
    e = __builtin_shufflevector(xy_e, c[2], 6, 1, 2, 7);
  } else {
    static_assert(W == 8);
    const Lanes<8> xy_a = __builtin_shufflevector(c[0], c[1], 0, 8, 0, 1, 9, 1, 2, 10);
    a = __builtin_shufflevector(xy_a, c[2], 0, 1, 8, 3, 4, 9, 6, 7);
    const Lanes<8> xy_b = __builtin_shufflevector(c[0], c[1], 0, 3, 11, 0, 4, 12, 0, 5);
    b = __builtin_shufflevector(xy_b, c[2], 10, 1, 2, 11, 4, 5, 12, 7);
    const Lanes<8> xy_e = __builtin_shufflevector(c[0], c[1], 13, 0, 6, 14, 0, 7, 15, 0);
    e = __builtin_shufflevector(xy_e, c[2], 0, 13, 2, 3, 14, 5, 6, 15);
  }
  store_lanes<W>(v[0].data(), a);
  store_lanes<W>(v[0].data() + W, b);
  store_lanes<W>(v[0].data() + std::ptrdiff_t{2} * W, e);
}

// W eight-double records (Lanes8, one per item) as eight lane vectors, one
// per field: c[f][k] = rec[k][f]. With W < 8 each record is W-wide pieces,
// each piece a W x W block.
template <int W>
[[gnu::always_inline]] inline void records8_to_lanes(const Lanes8* const (&rec)[W],
                                                     Lanes<W> (&c)[8]) {
#pragma GCC unroll 8
  for (int f0 = 0; f0 < 8; f0 += W) {
    Lanes<W> r[W];
#pragma GCC unroll 8
    for (int k = 0; k < W; ++k) r[k] = load_lanes<W>(reinterpret_cast<const double*>(rec[k]) + f0);
    transpose<W>(r);
    for (int j = 0; j < W; ++j) c[f0 + j] = r[j];
  }
}

// The inverse: rec[k][f] = c[f][k].
template <int W>
[[gnu::always_inline]] inline void lanes_to_records8(const Lanes<W> (&c)[8], Lanes8 (&rec)[W]) {
  if constexpr (W == 8) {
    for (int f = 0; f < 8; ++f) rec[f] = c[f];
    transpose<8>(rec);
  } else {
#pragma GCC unroll 8
    for (int f0 = 0; f0 < 8; f0 += W) {
      Lanes<W> r[W];
      for (int j = 0; j < W; ++j) r[j] = c[f0 + j];
      transpose<W>(r);
#pragma GCC unroll 8
      for (int k = 0; k < W; ++k) store_lanes<W>(reinterpret_cast<double*>(&rec[k]) + f0, r[k]);
    }
  }
}

}  // namespace pbms::simd
