#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <utility>

#include "kernels/half_neighbour_list.hpp"
#include "pbms/error.hpp"

using namespace pbms::dpd;

namespace {

// Uniformly random particles, some placed outside the box so that build()
// must wrap them.
DpdParticles random_particles(int count, const OrthogonalBox& box, unsigned seed) {
  std::mt19937_64 rng(seed);
  DpdParticles p;
  p.mass_per_type = {1.0};
  for (int i = 0; i < count; ++i) {
    Vec3 x{};
    for (int a = 0; a < 3; ++a) {
      std::uniform_real_distribution<double> u(box.lo[a] - 0.3 * box.length(a),
                                               box.hi[a] + 0.3 * box.length(a));
      x[a] = u(rng);
    }
    p.add(i + 1, 0, x);
  }
  return p;
}

// (i, j, shift code) of every pair within reach, by brute force.
std::set<std::tuple<std::size_t, std::size_t, int>> brute_force_pairs(const DpdParticles& p,
                                                                      const OrthogonalBox& box,
                                                                      double reach) {
  std::set<std::tuple<std::size_t, std::size_t, int>> pairs;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      Vec3 d{};
      for (int a = 0; a < 3; ++a) d[a] = p.x[i][a] - p.x[j][a];
      const Vec3 m = box.minimum_image(d);
      if (m[0] * m[0] + m[1] * m[1] + m[2] * m[2] >= reach * reach) continue;
      int code = 0;
      int stride = 1;
      for (int a = 0; a < 3; ++a) {
        const int s =
            static_cast<int>(std::lround((m[a] - d[a]) / (box.periodic[a] ? box.length(a) : 1.0)));
        code += (s + 1) * stride;
        stride *= 3;
      }
      pairs.emplace(i, j, code);
    }
  }
  return pairs;
}

std::set<std::tuple<std::size_t, std::size_t, int>> listed_pairs(const HalfNeighbourList& list) {
  std::set<std::tuple<std::size_t, std::size_t, int>> pairs;
  for (std::size_t i = 0; i < list.particle_count(); ++i) {
    for (std::size_t k = list.first(i); k < list.first(i + 1); ++k) {
      const auto e = list.entries()[k];
      const std::size_t j = HalfNeighbourList::neighbour(e);
      pairs.emplace(std::min(i, j), std::max(i, j), HalfNeighbourList::shift_code(e));
    }
  }
  return pairs;
}

}  // namespace

class DpdNeighbourListAxes : public ::testing::TestWithParam<std::array<bool, 3>> {};

TEST_P(DpdNeighbourListAxes, EqualsBruteForcePairList) {
  OrthogonalBox box;
  box.lo = {-3.0, 1.0, 0.5};
  box.hi = {27.0, 34.0, 23.5};  // 30 x 33 x 23 Å: 2, 3 and 2 cells of 11 Å
  box.periodic = GetParam();
  DpdParticles p = random_particles(400, box, 7);
  const DpdParticles unwrapped = p;
  HalfNeighbourList list(10.0, 1.0);
  list.build(p, box);

  // Wrapped into the box on periodic axes, with the crossings counted.
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      if (box.periodic[a]) {
        EXPECT_GE(p.x[i][a], box.lo[a]);
        EXPECT_LT(p.x[i][a], box.hi[a]);
      }
      EXPECT_NEAR(p.x[i][a] + p.image[i][a] * box.length(a), unwrapped.x[i][a], 1e-12);
    }
  }
  const auto expected = brute_force_pairs(p, box, 11.0);
  EXPECT_GT(expected.size(), 1000u);
  EXPECT_EQ(listed_pairs(list), expected);
  EXPECT_EQ(list.pair_count(), expected.size());  // each pair once
}

INSTANTIATE_TEST_SUITE_P(PeriodicFlags, DpdNeighbourListAxes,
                         ::testing::Values(std::array<bool, 3>{true, true, true},
                                           std::array<bool, 3>{false, false, false},
                                           std::array<bool, 3>{true, false, true},
                                           std::array<bool, 3>{false, true, false}));

TEST(DpdNeighbourList, ShiftGivesTheMinimumImageSeparation) {
  OrthogonalBox box;
  box.hi = {24.0, 24.0, 24.0};
  DpdParticles p;
  p.mass_per_type = {1.0};
  p.add(1, 0, {0.5, 12.0, 23.5});
  p.add(2, 0, {23.5, 12.0, 0.5});
  HalfNeighbourList list(3.0, 0.5);
  list.build(p, box);
  ASSERT_EQ(list.pair_count(), 1u);
  const auto e = list.entries()[0];
  const Vec3& s = list.shift(HalfNeighbourList::shift_code(e));
  EXPECT_DOUBLE_EQ(p.x[0][0] - p.x[1][0] + s[0], 1.0);
  EXPECT_DOUBLE_EQ(p.x[0][1] - p.x[1][1] + s[1], 0.0);
  EXPECT_DOUBLE_EQ(p.x[0][2] - p.x[1][2] + s[2], -1.0);
}

// The noise counter words kept per entry: the two ids of the pair, lower
// in the low half, whatever the order of the particles; none when not kept.
TEST(DpdNeighbourList, KeepsEachEntrysOrderedPairIdsOnlyWhenAsked) {
  OrthogonalBox box;
  box.hi = {20.0, 20.0, 20.0};
  DpdParticles p = random_particles(300, box, 11);
  // Ids that do not follow the index, and one past 2^31.
  for (std::size_t i = 0; i < p.size(); ++i) p.id[i] = static_cast<std::int64_t>(7919 * (300 - i));
  p.id[5] = (std::int64_t{1} << 31) + 3;
  HalfNeighbourList kept(4.0, 0.5);
  kept.build(p, box);
  ASSERT_GT(kept.pair_count(), 100u);
  ASSERT_NE(kept.pair_ids(), nullptr);
  for (std::size_t i = 0; i < kept.particle_count(); ++i) {
    for (std::size_t k = kept.first(i); k < kept.first(i + 1); ++k) {
      const auto a = static_cast<std::uint64_t>(p.id[i]);
      const auto b =
          static_cast<std::uint64_t>(p.id[HalfNeighbourList::neighbour(kept.entries()[k])]);
      EXPECT_EQ(kept.pair_ids()[k], (std::max(a, b) << 32) | std::min(a, b)) << "entry " << k;
    }
  }
  HalfNeighbourList plain(4.0, 0.5, false);
  plain.build(p, box);
  EXPECT_EQ(plain.pair_count(), kept.pair_count());
  EXPECT_EQ(plain.pair_ids(), nullptr);
}

TEST(DpdNeighbourList, NeedsRebuildOnlyBeyondHalfTheSkin) {
  OrthogonalBox box;
  box.hi = {30.0, 30.0, 30.0};
  DpdParticles p = random_particles(50, box, 3);
  HalfNeighbourList list(10.0, 1.0);
  EXPECT_TRUE(list.needs_rebuild(p));
  list.build(p, box);
  EXPECT_FALSE(list.needs_rebuild(p));
  p.x[17][1] += 0.49;
  EXPECT_FALSE(list.needs_rebuild(p));
  p.x[17][1] += 0.02;
  EXPECT_TRUE(list.needs_rebuild(p));
  list.build(p, box);
  EXPECT_FALSE(list.needs_rebuild(p));
  EXPECT_EQ(list.build_count(), 2);
}

TEST(DpdNeighbourList, RefusesAPeriodicBoxShorterThanTwiceTheReach) {
  OrthogonalBox box;
  box.hi = {21.9, 30.0, 30.0};
  DpdParticles p = random_particles(10, box, 1);
  HalfNeighbourList list(10.0, 1.0);
  EXPECT_THROW(list.build(p, box), pbms::Error);
  box.periodic[0] = false;
  EXPECT_NO_THROW(list.build(p, box));
}

TEST(DpdNeighbourList, RefusesNonPositiveCutoffAndNegativeSkin) {
  EXPECT_THROW(HalfNeighbourList(0.0, 1.0), pbms::Error);
  EXPECT_THROW(HalfNeighbourList(1.0, -0.1), pbms::Error);
}
