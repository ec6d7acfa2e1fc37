// Eight doubles that the compiler keeps in one AVX-512 register (two AVX2,
// four SSE2 ones) and computes on element-wise: the GCC/Clang vector
// extension, so one source serves every instruction set PBMS_ARCH picks.
// Used where a kernel has exactly eight of something: the corners of a grid
// cell, the fields of a packed node record.
#pragma once

#include <array>

namespace pbms {

// may_alias, as for the intrinsics' __m512d: arrays of records that hold
// Lanes8 are also read through double pointers (halo sums, output).
using Lanes8 = double __attribute__((vector_size(64), may_alias));

// Lanes first, first + 1, first + 2 as a 3-vector.
inline std::array<double, 3> lanes3(const Lanes8& l, int first) {
  return {l[first], l[first + 1], l[first + 2]};
}

}  // namespace pbms
