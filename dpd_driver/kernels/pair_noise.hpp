// The random number θ_ij of a DPD pair, drawn from a counter-based generator
// (Random123 Philox4x64-10) so that it depends only on the run seed, the
// unordered pair of global ids and the step: the same on every rank and for
// every decomposition, with no generator state to store or communicate (the
// scheme HOOMD-blue uses).
//
// Key and counter layout (two and four 64-bit words):
//   key     = { seed, kDpdPairNoiseStream }
//   counter = { min(id_a, id_b), max(id_a, id_b), step, 0 }
// The stream word keeps this use of the seed apart from any other Philox
// draw a driver keys with the same seed; the last counter word is free for a
// second draw of the same pair and step.
//
// Distribution: Box–Muller on the first two 64-bit outputs (each turned into
// a uniform in the open interval (0, 1) from its top 53 bits), keeping the
// cosine branch. An exact unit Gaussian costs a log, a sqrt and a cos per
// pair; the cheaper uniform·√3 would match mean and variance only, and a
// Gaussian keeps the random force's increments Gaussian at any time step.
#pragma once

#include <cstdint>

namespace pbms::dpd {

// "DPDpair" in ASCII.
inline constexpr std::uint64_t kDpdPairNoiseStream = 0x0044504450616972ULL;

// Zero mean, unit variance; symmetric in (id_a, id_b).
double pair_gaussian_pair_noise(std::uint64_t seed, std::int64_t id_a, std::int64_t id_b,
                                std::int64_t step);

}  // namespace pbms::dpd
