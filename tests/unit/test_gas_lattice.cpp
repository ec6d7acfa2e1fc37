// Where the gas around a concurrent stage's body starts (gas_lattice).
#include <gtest/gtest.h>

#include <random>

#include "pbms/coupling/gas_lattice.hpp"

using namespace pbms;
using namespace pbms::coupling;
using geometry::Vec3;

namespace {

// An fcc block of n³ cells of edge a from `lo`, faces closed: the corner
// lattice's (n+1)³ sites and the face centres that lie inside it.
std::vector<Vec3> closed_fcc_block(int n, double a, const Vec3& lo) {
  std::vector<Vec3> x;
  const double h = 0.5 * a;
  for (int i = 0; i <= 2 * n; ++i) {
    for (int j = 0; j <= 2 * n; ++j) {
      for (int k = 0; k <= 2 * n; ++k) {
        if ((i + j + k) % 2 != 0) continue;
        x.push_back({lo[0] + i * h, lo[1] + j * h, lo[2] + k * h});
      }
    }
  }
  return x;
}

GasParams inclusion_gas() {
  GasParams g;
  g.spacing = 7.23;
  g.origin = {0.0, 0.0, 0.0};
  g.clearance = 0.75 * g.spacing;
  return g;
}

}  // namespace

// The seed's inclusion (§6.2.1): a 20 a_cg box, the cube of 10 a_cg (4,631
// particles) in its middle, 7,930 gas points = 21³ - 11³.
TEST(GasLattice, TheSeedsInclusionLeavesTwentyOneCubedLessElevenCubedSites) {
  const auto cube = closed_fcc_block(10, 7.23, {36.15, 36.15, 36.15});
  ASSERT_EQ(cube.size(), 4631U);
  const geometry::Box box{{0.0, 0.0, 0.0}, {144.6, 144.6, 144.6}};
  const auto sites = gas_sites(inclusion_gas(), box, {false, false, false}, cube);
  EXPECT_EQ(sites.size(), 21U * 21 * 21 - 11U * 11 * 11);
  // None is within the clearance of the cube; the nearest lie a spacing off
  // its faces.
  for (const bool near : near_body(sites, cube, 0.75 * 7.23)) EXPECT_FALSE(near);
  const auto one_spacing = near_body(sites, cube, 7.23 + 1e-9);
  EXPECT_GT(std::count(one_spacing.begin(), one_spacing.end(), true), 0);
}

// On a periodic axis the upper face is the lower face's image: its sites
// are not laid twice.
TEST(GasLattice, PeriodicAxesLeaveOutTheUpperFace) {
  const geometry::Box box{{0.0, 0.0, 0.0}, {72.3, 72.3, 72.3}};
  EXPECT_EQ(gas_sites(inclusion_gas(), box, {false, false, false}, {}).size(), 11U * 11 * 11);
  EXPECT_EQ(gas_sites(inclusion_gas(), box, {true, false, false}, {}).size(), 10U * 11 * 11);
}

// The binned search answers as the all-pairs one does.
TEST(GasLattice, NearBodyAgreesWithAllPairs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  std::vector<Vec3> body(300), points(500);
  for (auto& x : body) x = {u(rng), u(rng), u(rng)};
  for (auto& x : points) x = {u(rng), u(rng), u(rng)};
  const double d = 3.3;
  const auto near = near_body(points, body, d);
  for (std::size_t i = 0; i < points.size(); ++i) {
    bool any = false;
    for (const auto& b : body) {
      double s = 0.0;
      for (std::size_t a = 0; a < 3; ++a) s += (points[i][a] - b[a]) * (points[i][a] - b[a]);
      any = any || s <= d * d;
    }
    EXPECT_EQ(near[i], any) << "point " << i;
  }
}
