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
  const auto sites = gas_sites(inclusion_gas(), box, {false, false, false}, cube, 7.23);
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
  EXPECT_EQ(gas_sites(inclusion_gas(), box, {false, false, false}, {}, 7.23).size(), 11U * 11 * 11);
  EXPECT_EQ(gas_sites(inclusion_gas(), box, {true, false, false}, {}, 7.23).size(), 10U * 11 * 11);
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

// A gas lattice of half the crystal's lattice constant, aligned with it,
// has a site on every fcc site and every octahedral hole of a block: the
// (2n+1)³ points of spacing a/2 that the closed block spans. All of them
// go, the holes on its faces and edges included, and no site outside: the
// next plane out, half a lattice constant off the faces, is kept whole.
// With the clearance alone the holes inside would be gas.
TEST(GasLattice, AFinerLatticeLeavesNoGasInTheCrystalsHoles) {
  const double a = 7.23;
  const int n = 4;
  const auto block = closed_fcc_block(n, a, {4 * a, 4 * a, 4 * a});
  GasParams g;
  g.spacing = 0.5 * a;
  g.origin = {0.0, 0.0, 0.0};
  g.clearance = 0.75 * g.spacing;
  const geometry::Box box{{0.0, 0.0, 0.0}, {(2 * 4 + n) * a, (2 * 4 + n) * a, (2 * 4 + n) * a}};
  const std::size_t lattice = (2 * (2 * 4 + n) + 1) * (2 * (2 * 4 + n) + 1) * (2 * (2 * 4 + n) + 1);
  const std::size_t spanned = (2 * n + 1) * (2 * n + 1) * (2 * n + 1);
  EXPECT_EQ(gas_sites(g, box, {false, false, false}, block, a).size(), lattice - spanned);
  EXPECT_LT(gas_sites(g, box, {false, false, false}, block, 0.0).size(),
            lattice - block.size() + 1);
  EXPECT_GT(gas_sites(g, box, {false, false, false}, block, 0.0).size(), lattice - spanned + 300);
}

// The rule holds under thermal displacements: each site moved at random by
// up to 0.3 Å (copper's mesoparticles at 298 K move about 0.1 Å rms).
TEST(GasLattice, TheHolesAreFoundInAThermalCrystal) {
  const double a = 7.23;
  auto block = closed_fcc_block(4, a, {4 * a, 4 * a, 4 * a});
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.3 / std::sqrt(3.0), 0.3 / std::sqrt(3.0));
  for (auto& x : block) {
    for (auto& c : x) c += u(rng);
  }
  GasParams g;
  g.spacing = 0.5 * a;
  g.origin = {0.0, 0.0, 0.0};
  g.clearance = 0.75 * g.spacing;
  const geometry::Box box{{0.0, 0.0, 0.0}, {12 * a, 12 * a, 12 * a}};
  EXPECT_EQ(gas_sites(g, box, {false, false, false}, block, a).size(), 25U * 25 * 25 - 9U * 9 * 9);
}
