#include "kernels/pair_noise.hpp"

#include <Random123/philox.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pbms::dpd {

namespace {

// (k + 0.5) / 2^53 for the top 53 bits k: never 0, so the log is finite.
double open_unit_interval(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

}  // namespace

double pair_gaussian_pair_noise(std::uint64_t seed, std::int64_t id_a, std::int64_t id_b,
                                std::int64_t step) {
  using Generator = r123::Philox4x64;
  const Generator::key_type key = {{seed, kDpdPairNoiseStream}};
  const Generator::ctr_type counter = {{static_cast<std::uint64_t>(std::min(id_a, id_b)),
                                        static_cast<std::uint64_t>(std::max(id_a, id_b)),
                                        static_cast<std::uint64_t>(step), 0}};
  const Generator::ctr_type bits = Generator()(counter, key);
  const double u1 = open_unit_interval(bits[0]);
  const double u2 = open_unit_interval(bits[1]);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace pbms::dpd
