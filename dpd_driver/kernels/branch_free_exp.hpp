// exp(x) without branches or calls, so that a loop over pairs that calls it
// vectorises (std::exp is an opaque library call that keeps the Morse loop
// scalar). Within 2 ulp of std::exp for x in [−708, 708]; outside that range
// the result is wrong (callers check their argument range once, up front: a
// clamp here would be a select that keeps GCC from vectorising the loop).
#pragma once

#include <bit>
#include <cstdint>

namespace pbms::dpd {

inline constexpr double kBranchFreeExpLimit = 708.0;

inline double branch_free_exp(double x) {
  constexpr double kLog2e = 1.4426950408889634;
  // ln 2 split so that k · kLn2High is exact for |k| < 2^11.
  constexpr double kLn2High = 0x1.62e42fefa3800p-1;
  constexpr double kLn2Low = 0x1.ef35793c76730p-45;
  // Adding 1.5 · 2^52 rounds to an integer held in the low mantissa bits.
  constexpr double kShifter = 0x1.8p52;

  const double shifted = x * kLog2e + kShifter;
  const double k = shifted - kShifter;
  const double r = (x - k * kLn2High) - k * kLn2Low;  // |r| ≤ ln2 / 2
  // Taylor series to r^12: the remainder r^13/13! < 2e-16 for |r| ≤ 0.347.
  double p = 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  const std::int64_t exponent =
      std::bit_cast<std::int64_t>(shifted) - std::bit_cast<std::int64_t>(kShifter);
  return p * std::bit_cast<double>((exponent + 1023) << 52);
}

}  // namespace pbms::dpd
