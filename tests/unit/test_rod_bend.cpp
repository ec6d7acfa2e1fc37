// The bend of a rod (analysis/rod_bend) against the sagitta of a circular
// arc, computed here from its radius and chord.
#include <gtest/gtest.h>

#include <cmath>

#include "pbms/analysis/rod_bend.hpp"

using pbms::analysis::rod_bend;

namespace {

// Slabs of a rod whose centre line is x(z): `n` members at that centroid.
template <class Line>
std::vector<std::array<double, 4>> slabs_along(Line x, int count, double n) {
  std::vector<std::array<double, 4>> s;
  for (int k = 0; k < count; ++k) {
    const double z = 7.23 * k;
    s.push_back({n, n * x(z), n * 1.5, n * z});
  }
  return s;
}

}  // namespace

TEST(RodBend, AStraightRodHasNone) {
  EXPECT_NEAR(rod_bend(slabs_along([](double z) { return 0.3 * z; }, 19, 200.0)), 0.0, 1e-12);
}

// An arc of radius R through the rod's ends, over a chord of 18 a: the
// sagitta is R - sqrt(R² - (c/2)²) at the middle slab.
TEST(RodBend, AnArcBendsByItsSagitta) {
  const double R = 400.0, half = 9 * 7.23;
  const auto arc = [&](double z) { return std::sqrt(R * R - (z - half) * (z - half)); };
  const double sagitta = R - std::sqrt(R * R - half * half);
  EXPECT_NEAR(rod_bend(slabs_along(arc, 19, 200.0)), sagitta, 1e-9 * R);
}

TEST(RodBend, EmptySlabsAreSkipped) {
  auto s = slabs_along([](double z) { return 0.1 * z; }, 10, 5.0);
  s[4] = {0.0, 0.0, 0.0, 0.0};
  EXPECT_NEAR(rod_bend(s), 0.0, 1e-12);
  EXPECT_EQ(rod_bend({s[0], s[1]}), 0.0);
}

// A rough end face leaves a few particles in a slab past the last whole
// one; their centroid, off the axis, must not tilt the chord.
TEST(RodBend, APartialEndSlabIsLeftOut) {
  auto s = slabs_along([](double z) { return 0.2 * z; }, 19, 200.0);
  const double z = 7.23 * 19;
  s.push_back({4.0, 4.0 * (0.2 * z - 11.0), 4.0 * (1.5 + 14.0), 4.0 * z});
  EXPECT_NEAR(rod_bend(s), 0.0, 1e-12);
  // A slab with half the others' members still counts.
  s.back() = {100.0, 100.0 * (0.2 * z + 3.0), 100.0 * 1.5, 100.0 * z};
  EXPECT_GT(rod_bend(s), 1.0);
}
