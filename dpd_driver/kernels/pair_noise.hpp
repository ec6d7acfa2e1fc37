// The random number θ_ij of a DPD pair, drawn from a counter-based generator
// (Random123's Philox) so that it depends only on the run seed, the
// unordered pair of global ids and the step: the same on every rank and for
// every decomposition, with no generator state to store or communicate (the
// scheme HOOMD-blue uses).
//
// Key and counter layout (32-bit words), with s = splitmix64(seed ^
// kDpdPairNoiseStream):
//   uniform   Philox2x32-10, key = low half of s + step (mod 2^32),
//             counter = { min(id_a, id_b), max(id_a, id_b) };
//   gaussian  Philox4x32-10, key = { low, high half of s },
//             counter = { min(id_a, id_b), max(id_a, id_b), low, high half of step }.
// Ids must therefore lie in [0, 2^32); check_pair_noise_ids() says so before
// a run starts. The stream constant keeps this use of a seed apart from every
// other Philox draw keyed with the same seed.
//
// Why uniform θ takes the smaller generator: it needs 52 bits, which the 64
// of Philox2x32 hold, and a Philox2x32 round is half the work of a 4x32 one;
// the draw is most of the thermostat's cost. The price is the 32-bit key,
// which carries seed and step together, as HOOMD-blue's DPD keyed Saru with
// seed + timestep. Within a run every step has its own key for 2^32 steps.
// Two runs whose seeds give low halves d apart draw the same numbers d steps
// apart, which for runs of N steps happens with probability about 2N/2^32
// per pair of seeds (5e-4 for a million steps). Gaussian θ needs 104 bits,
// so it keeps Philox4x32 and a key with no such overlap.
//
// Distributions (θ has zero mean and unit variance in both):
//   gaussian  Box–Muller on two uniforms, each from 53 bits of the output
//             (words 1:0 and 3:2), keeping the cosine branch;
//   uniform   √3 (2u − 1), u from words 1:0. The choice of Groot & Warren
//             (1997) and of HOOMD-blue's DPD: the random force enters the
//             equations of motion only through its first two moments, so the
//             stationary state is the same as with Gaussian θ to O(Δt).
//
// Speed is the point of this file: the draw is most of the thermostat's
// cost. The force loop's own path (pair_friction_coefficients.hpp) draws
// uniform θ in registers with the same bits. Philox runs 8 (AVX-512) or 4
// (AVX2) pairs to a register when the processor has the instructions,
// chosen at run time; it is integer arithmetic, so every path gives the
// same bits. The log and cos of Box–Muller are branch-free polynomials
// (pair_noise.cpp) rather than libm calls, so that they vectorise and give
// the same value in a vector lane as in the scalar remainder: a pair's θ
// must not depend on where in a batch it fell, which the decomposition
// decides.
#pragma once

#include <cstdint>
#include <string_view>

#include "kernels/dpd_particles.hpp"

namespace pbms::dpd {

// "DPDpair" in ASCII.
inline constexpr std::uint64_t kDpdPairNoiseStream = 0x0044504450616972ULL;

enum class PairNoiseDistribution { kGaussian, kUniform };

// The name a user writes ("gaussian", "uniform"); throws Error otherwise.
PairNoiseDistribution pair_noise_distribution(std::string_view name);

struct PairNoise {
  PairNoise() = default;
  PairNoise(std::uint64_t seed, PairNoiseDistribution distribution);
  // Philox2x32's key for uniform θ at a step.
  std::uint32_t uniform_key(std::int64_t step) const {
    return key[0] + static_cast<std::uint32_t>(static_cast<std::uint64_t>(step));
  }
  std::uint32_t key[2] = {0, 0};
  PairNoiseDistribution distribution = PairNoiseDistribution::kGaussian;
};

// θ for `count` pairs of one step: theta[m] belongs to the ids
// (id_low[m], id_high[m]), id_low[m] ≤ id_high[m]. Any count ≥ 0.
void pair_noise_batch(const PairNoise& noise, const std::uint32_t* id_low,
                      const std::uint32_t* id_high, std::int64_t step, int count, double* theta);

// One pair, in either order; bit-identical to the batch.
double pair_noise(const PairNoise& noise, std::int64_t id_a, std::int64_t id_b, std::int64_t step);

// Throws Error naming the first id outside [0, 2^32) (only ids in 32 bits
// fit the counter).
void check_pair_noise_ids(const DpdParticles& particles);

}  // namespace pbms::dpd
