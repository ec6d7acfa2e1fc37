// Layout changes between records and lanes for kernels that run one item
// per SIMD lane (eight material points at once): an 8 x 8 transpose, and
// the split of eight 3-vectors stored one after another into one register
// per component and back. Shuffles only, so the values are moved, never
// rounded.
#pragma once

#include <array>
#include <cstddef>

#include "pbms/simd/lanes8.hpp"

namespace pbms::simd {

// r[i][j] becomes r[j][i]: eight records of eight fields in, eight fields
// across eight records out (three rounds of two-register shuffles).
[[gnu::always_inline]] inline void transpose8(Lanes8 (&r)[8]) {
  Lanes8 t[8];
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

// Eight 3-vectors at v (24 doubles, x y z x y z ...) as one register per
// component: c[d][k] = v[k][d].
[[gnu::always_inline]] inline void deinterleave3(const std::array<double, 3>* v, Lanes8 (&c)[3]) {
  Lanes8 a, b, e;
  __builtin_memcpy(&a, v[0].data(), sizeof a);
  __builtin_memcpy(&b, v[0].data() + 8, sizeof b);
  __builtin_memcpy(&e, v[0].data() + 16, sizeof e);
  // a = x0 y0 z0 x1 y1 z1 x2 y2, b = z2 x3 y3 z3 x4 y4 z4 x5,
  // e = y5 z5 x6 y6 z6 x7 y7 z7.
  const Lanes8 x = __builtin_shufflevector(a, b, 0, 3, 6, 9, 12, 15, 0, 0);
  const Lanes8 y = __builtin_shufflevector(a, b, 1, 4, 7, 10, 13, 0, 0, 0);
  const Lanes8 z = __builtin_shufflevector(a, b, 2, 5, 8, 11, 14, 0, 0, 0);
  c[0] = __builtin_shufflevector(x, e, 0, 1, 2, 3, 4, 5, 10, 13);
  c[1] = __builtin_shufflevector(y, e, 0, 1, 2, 3, 4, 8, 11, 14);
  c[2] = __builtin_shufflevector(z, e, 0, 1, 2, 3, 4, 9, 12, 15);
}

// The inverse of deinterleave3: writes the 24 doubles at v.
[[gnu::always_inline]] inline void interleave3(const Lanes8 (&c)[3], std::array<double, 3>* v) {
  // First the three 8-wide pieces of the x y z stream, each from two
  // registers, then the third register's lanes put in.
  const Lanes8 xy_a = __builtin_shufflevector(c[0], c[1], 0, 8, 0, 1, 9, 1, 2, 10);
  const Lanes8 a = __builtin_shufflevector(xy_a, c[2], 0, 1, 8, 3, 4, 9, 6, 7);
  const Lanes8 xy_b = __builtin_shufflevector(c[0], c[1], 0, 3, 11, 0, 4, 12, 0, 5);
  const Lanes8 b = __builtin_shufflevector(xy_b, c[2], 10, 1, 2, 11, 4, 5, 12, 7);
  const Lanes8 xy_e = __builtin_shufflevector(c[0], c[1], 13, 0, 6, 14, 0, 7, 15, 0);
  const Lanes8 e = __builtin_shufflevector(xy_e, c[2], 0, 13, 2, 3, 14, 5, 6, 15);
  __builtin_memcpy(v[0].data(), &a, sizeof a);
  __builtin_memcpy(v[0].data() + 8, &b, sizeof b);
  __builtin_memcpy(v[0].data() + 16, &e, sizeof e);
}

// Eight records of nine doubles stored one after another (a 3 x 3 matrix,
// a point's state) as one register per field: c[f][k] is field f of record
// k at base[9 k + f]. Fields 0-7 go through one transpose; field 8 lane by
// lane.
[[gnu::always_inline]] inline void load_records9(const double* base, Lanes8 (&c)[9]) {
  Lanes8 r[8];
  for (std::ptrdiff_t k = 0; k < 8; ++k) __builtin_memcpy(&r[k], base + 9 * k, sizeof(Lanes8));
  transpose8(r);
  for (int f = 0; f < 8; ++f) c[f] = r[f];
  c[8] = Lanes8{base[8], base[17], base[26], base[35], base[44], base[53], base[62], base[71]};
}

// The inverse of load_records9: writes the 72 doubles at base.
[[gnu::always_inline]] inline void store_records9(const Lanes8 (&c)[9], double* base) {
  Lanes8 r[8];
  for (int f = 0; f < 8; ++f) r[f] = c[f];
  transpose8(r);
  for (std::ptrdiff_t k = 0; k < 8; ++k) __builtin_memcpy(base + 9 * k, &r[k], sizeof(Lanes8));
  for (int k = 0; k < 8; ++k) base[9 * k + 8] = c[8][k];
}

}  // namespace pbms::simd
