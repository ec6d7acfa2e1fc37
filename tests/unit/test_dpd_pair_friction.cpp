#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "integrators/shardlow_sweep.hpp"
#include "kernels/dpd_pair_friction.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/kinetic_sums.hpp"
#include "kernels/pair_friction_coefficients.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

using namespace pbms::dpd;
using pbms::units::kBoltzmann;
using pbms::units::kMvv2e;

namespace {

constexpr double kMass = 508.37;  // g/mol
constexpr double kCutoff = 10.0;  // Å

// Two particles r apart along (1, 2, 2)/3 in a large free box, approaching
// each other along the line of centres plus a sideways slip.
struct Pair {
  DpdParticles particles;
  OrthogonalBox box;
  HalfNeighbourList list{kCutoff, 0.5};
  Vec3 e{1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0};

  explicit Pair(double r, std::int64_t id_a = 7, std::int64_t id_b = 3) {
    box.hi = {100.0, 100.0, 100.0};
    box.periodic = {false, false, false};
    particles.mass_per_type = {kMass, 2.0 * kMass};
    particles.add(id_a, 0, {50.0 + r * e[0], 50.0 + r * e[1], 50.0 + r * e[2]}, {-1.0, 0.5, 0.3});
    particles.add(id_b, 1, {50.0, 50.0, 50.0}, {0.2, -0.4, 1.0});
    list.build(particles, box);
  }
  // The one pair, as a Shardlow sweep sees it.
  [[nodiscard]] std::vector<ShardlowPair> sweep_pairs() const {
    ShardlowPairOrder order(box, kCutoff, 0.0);
    order.build(particles, box, [](const Vec3&) { return true; });
    std::vector<ShardlowPair> all;
    for (int c = 0; c < ShardlowPairOrder::kColours; ++c) {
      for (const ShardlowPair& p : order.colour(c)) all.push_back(p);
    }
    return all;
  }
  [[nodiscard]] double approach_speed() const {
    double w = 0.0;
    for (int a = 0; a < 3; ++a) w += e[a] * (particles.v[0][a] - particles.v[1][a]);
    return w;
  }
};

}  // namespace

TEST(DpdPairFriction, DissipativeForceIsTheGrootWarrenFormulaAndObeysNewtonsThirdLaw) {
  const double r = 6.0;
  Pair pair(r);
  const DpdPairFriction friction{5.0, kCutoff, 0.0, 11};  // T = 0: no noise
  add_dissipative_random_forces(pair.particles, pair.particles.v, pair.list, friction, 0, 0.01);
  const double w_r = 1.0 - r / kCutoff;
  const double expected = -5.0 * w_r * w_r * pair.approach_speed() * kMvv2e;  // eV/Å along e
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(pair.particles.f[0][a], expected * pair.e[a], 1e-15);
    EXPECT_EQ(pair.particles.f[0][a], -pair.particles.f[1][a]);
  }
}

TEST(DpdPairFriction, NothingActsBeyondTheDpdCutoff) {
  Pair pair(kCutoff + 0.2);
  const DpdPairFriction friction{5.0, kCutoff, 298.0, 11};
  add_dissipative_random_forces(pair.particles, pair.particles.v, pair.list, friction, 0, 0.01);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(pair.particles.f[0][a], 0.0);
}

TEST(DpdPairFriction, RandomForceIsTheSameWhicheverParticleIsStoredFirst) {
  const DpdPairFriction friction{5.0, kCutoff, 298.0, 11};
  Pair forward(6.0, 7, 3);
  Pair swapped(6.0, 3, 7);
  for (Pair* p : {&forward, &swapped}) p->particles.v.assign(2, {0.0, 0.0, 0.0});
  add_dissipative_random_forces(forward.particles, forward.particles.v, forward.list, friction, 42,
                                0.01);
  add_dissipative_random_forces(swapped.particles, swapped.particles.v, swapped.list, friction, 42,
                                0.01);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(forward.particles.f[0][a], swapped.particles.f[0][a]);
}

TEST(DpdPairFriction, RandomForceVarianceIsTwoGammaKTOverDt) {
  const double r = 5.5;
  const double gamma = 3.0, temperature = 400.0, dt = 0.005;
  const DpdPairFriction friction{gamma, kCutoff, temperature, 99};
  Pair pair(r);
  pair.particles.v.assign(2, {0.0, 0.0, 0.0});
  const int draws = 40000;
  double sum = 0.0, sum_sq = 0.0;
  for (int step = 0; step < draws; ++step) {
    pair.particles.zero_forces();
    add_dissipative_random_forces(pair.particles, pair.particles.v, pair.list, friction, step, dt);
    double along = 0.0;
    for (int a = 0; a < 3; ++a) along += pair.particles.f[0][a] * pair.e[a];
    sum += along;
    sum_sq += along * along;
  }
  const double w_r = 1.0 - r / kCutoff;
  const double expected = 2.0 * gamma * kBoltzmann * temperature * kMvv2e * w_r * w_r / dt;
  const double variance = sum_sq / draws - (sum / draws) * (sum / draws);
  // The sample variance of a Gaussian has relative standard error sqrt(2/n) = 0.7 %.
  EXPECT_NEAR(variance / expected, 1.0, 0.03);
  EXPECT_NEAR(sum / draws, 0.0, 4.0 * std::sqrt(expected / draws));
}

TEST(DpdShardlowSweep, ConservesMomentumAndDecaysTheApproachSpeedAsTheExactFrictionOde) {
  // At T = 0 the pair ODE is μ dw/dt = −γ w_D w for the approach speed w: w
  // decays as exp(−γ w_D t / μ). The two half steps are a second-order
  // (trapezoidal) solution: 100 steps at γ w_D Δt/μ ≈ 0.01 agree to ~1e-5.
  const double r = 5.0;
  Pair pair(r);
  const double gamma = 1500.0, dt = 0.01;
  const DpdPairFriction friction{gamma, kCutoff, 0.0, 5};
  const Vec3 momentum = total_momentum(pair.particles);
  const double w0 = pair.approach_speed();
  const int steps = 100;
  const auto pairs = pair.sweep_pairs();
  ASSERT_EQ(pairs.size(), 1u);
  for (int step = 0; step < steps; ++step)
    shardlow_sweep(pair.particles, pairs, friction, step, dt);
  const double reduced_mass = kMass * 2.0 * kMass / (3.0 * kMass);
  const double w_d = (1.0 - r / kCutoff) * (1.0 - r / kCutoff);
  const double exact = w0 * std::exp(-gamma * w_d * steps * dt / reduced_mass);
  EXPECT_NEAR(pair.approach_speed() / exact, 1.0, 1e-4);
  const Vec3 after = total_momentum(pair.particles);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(after[a], momentum[a], 1e-12 * kMass);
}

TEST(DpdShardlowSweep, DpdeMovesAllTheKineticEnergyItTakesIntoTheInternalEnergies) {
  Pair pair(5.2);
  const double heat_capacity = 21.0 * kBoltzmann;
  pair.particles.internal_energy = {heat_capacity * 250.0, heat_capacity * 400.0};
  const DpdPairFriction friction{50.0, kCutoff, 0.0, 17};
  const double before = kinetic_energy(pair.particles) + internal_energy_sum(pair.particles);
  const auto pairs = pair.sweep_pairs();
  ASSERT_EQ(pairs.size(), 1u);
  for (int step = 0; step < 1000; ++step) {
    shardlow_sweep_energy_conserving(pair.particles, pairs, friction, heat_capacity, step, 0.01);
  }
  const double after = kinetic_energy(pair.particles) + internal_energy_sum(pair.particles);
  EXPECT_NEAR(after, before, 1e-13 * before);
  // The relative motion exchanged energy with the internal energies: the test
  // is not passing vacuously.
  EXPECT_GT(std::abs(pair.particles.internal_energy[0] - heat_capacity * 250.0), 1e-4);
}

// The batch kernel of the force loop (AVX-512 with Philox in registers, or
// the portable path) against the formula written out with pair_noise(), for
// both θ distributions and a count that leaves partial vectors.
TEST(DpdPairFriction, BatchCoefficientsMatchTheFormulaOnEveryPath) {
  constexpr int kCount = 150;
  const std::vector<Vec3> unused_velocity;
  std::vector<std::uint64_t> id_pair(kCount);
  std::vector<double> r2(kCount), force_over_r(kCount);
  for (int m = 0; m < kCount; ++m) {
    const std::uint64_t a = 1 + 7919u * static_cast<std::uint64_t>(m);
    const std::uint64_t b = 40000000u - 104729u * static_cast<std::uint64_t>(m);
    id_pair[m] = std::max(a, b) << 32 | std::min(a, b);
    // r from 4 to 11 Å: some pairs beyond the 10 Å cutoff, where w = 0.
    const double r = 4.0 + 7.0 * m / kCount;
    r2[m] = r * r;
    force_over_r[m] = 0.01 * std::sin(m);
  }
  for (const PairNoiseDistribution noise :
       {PairNoiseDistribution::kUniform, PairNoiseDistribution::kGaussian}) {
    const DpdPairFriction friction{0.2, kCutoff, 298.0, 123, noise};
    const std::int64_t step = 4'294'967'296LL + 17;  // both step words in use
    const PairFrictionTerm term(friction, unused_velocity, step, 0.01);
    for (const SimdPath path : {SimdPath::kPortable, SimdPath::kAvx512}) {
      if (!simd_path_supported(path)) continue;
      std::vector<double> total(kCount), drag(kCount);
      pair_friction_coefficients(path, term, id_pair.data(), r2.data(), force_over_r.data(), kCount,
                                 total.data(), drag.data());
      for (int m = 0; m < kCount; ++m) {
        const double r = std::sqrt(r2[m]);
        const double w_over_r = std::max(0.0, 1.0 - r / kCutoff) / r;
        const double theta = pair_noise(term.noise, static_cast<std::int64_t>(id_pair[m] >> 32),
                                        static_cast<std::int64_t>(id_pair[m] & 0xffffffffu), step);
        const double expected_total = force_over_r[m] + term.noise_factor * theta * w_over_r;
        const double expected_drag = term.friction_factor * w_over_r * w_over_r;
        // w = 1 − r/r_c cancels near the cutoff, so its rounding is
        // measured against the size the terms would have at w = 1.
        const double noise_scale = term.noise_factor * std::max(1.0, std::abs(theta)) / r;
        EXPECT_NEAR(total[m], expected_total, 1e-14 * (std::abs(force_over_r[m]) + noise_scale))
            << "pair " << m;
        EXPECT_NEAR(drag[m], expected_drag, 1e-14 * term.friction_factor / r2[m]) << "pair " << m;
      }
    }
  }
}

TEST(DpdPairFriction, RefusesAListBuiltWithoutThePairIds) {
  Pair pair(6.0);
  HalfNeighbourList plain(kCutoff, 0.5, false);
  plain.build(pair.particles, pair.box);
  const DpdPairFriction friction{5.0, kCutoff, 298.0, 11};
  EXPECT_THROW(
      add_dissipative_random_forces(pair.particles, pair.particles.v, plain, friction, 0, 0.01),
      pbms::Error);
}
