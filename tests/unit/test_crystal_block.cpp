// A crystal block's edges along its own axes (analysis/crystal_block): an
// fcc block built here, turned, strained along its own axes and shaken,
// against the edges of the strained lattice computed here.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "pbms/analysis/crystal_block.hpp"
#include "pbms/error.hpp"

using pbms::analysis::block_edges;
using pbms::analysis::BlockPoint;
using pbms::analysis::BlockSums;
using pbms::analysis::fit_block_sites;

namespace {

constexpr double kA = 7.23;  // the coarse lattice constant, Å
constexpr int kCells = 10;   // the inclusion's cube: 4,631 sites

// The fcc sites of a block of kCells³ cells with closed faces, centred on
// the origin, as plane indices (an fcc site has an even index sum).
std::vector<std::array<int, 3>> fcc_block() {
  std::vector<std::array<int, 3>> sites;
  for (int i = 0; i <= 2 * kCells; ++i) {
    for (int j = 0; j <= 2 * kCells; ++j) {
      for (int k = 0; k <= 2 * kCells; ++k) {
        if ((i + j + k) % 2 == 0) sites.push_back({i - kCells, j - kCells, k - kCells});
      }
    }
  }
  return sites;
}

// Rodrigues' rotation by `deg` about a unit axis.
std::array<std::array<double, 3>, 3> rotation(std::array<double, 3> u, double deg) {
  const double n = std::hypot(u[0], u[1], u[2]);
  for (double& c : u) c /= n;
  const double t = deg * std::numbers::pi / 180.0, c = std::cos(t), s = std::sin(t);
  std::array<std::array<double, 3>, 3> R{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0.0) + (1.0 - c) * u[i] * u[j];
  }
  R[0][1] -= s * u[2];
  R[0][2] += s * u[1];
  R[1][0] += s * u[2];
  R[1][2] -= s * u[0];
  R[2][0] -= s * u[1];
  R[2][1] += s * u[0];
  return R;
}

// The block strained by `strain` along its own axes, turned by `deg` about
// `axis`, moved to `at`, each particle shaken by a normal `noise` (Å).
std::vector<BlockPoint> placed(const std::array<double, 3>& strain, std::array<double, 3> axis,
                               double deg, const BlockPoint& at, double noise, unsigned seed) {
  const auto R = rotation(axis, deg);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> shake(0.0, noise);
  std::vector<BlockPoint> x;
  for (const auto& s : fcc_block()) {
    std::array<double, 3> b{};
    for (int a = 0; a < 3; ++a) b[a] = 0.5 * kA * s[a] * (1.0 + strain[a]);
    BlockPoint p{};
    for (int i = 0; i < 3; ++i) {
      p[i] = at[i] + R[i][0] * b[0] + R[i][1] * b[1] + R[i][2] * b[2];
      if (noise > 0.0) p[i] += shake(rng);
    }
    x.push_back(p);
  }
  return x;
}

pbms::analysis::BlockEdges measure(const std::vector<BlockPoint>& x,
                                   const pbms::analysis::BlockSites& sites) {
  BlockSums sums;
  for (std::size_t p = 0; p < x.size(); ++p) sums.add(sites, p, x[p]);
  return block_edges(sites, sums);
}

}  // namespace

// The strained edges are (n + 1) plane spacings: 21 × a/2 × (1 + e). The
// shake (σ = 0.15 Å) moves a face plane's mean by σ/√220, an edge by √2
// times that times 21/20: 0.011 Å; the bound is four of those.
TEST(CrystalBlock, ATurnedStrainedShakenCubeGivesItsOwnEdges) {
  const std::array<double, 3> strain{-0.01, -0.02, 0.015};
  const double sigma = 0.15;
  const double bound = 4.0 * std::sqrt(2.0) * sigma / std::sqrt(220.0) * 21.0 / 20.0;
  for (double deg : {0.0, 2.0, 7.5, 15.0}) {
    const auto x = placed(strain, {0.3, -0.8, 0.5}, deg, {72.3, 70.1, 74.9}, sigma, 7);
    const auto sites = fit_block_sites(x, 0.5 * kA);
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_EQ(sites.faces[a][1] - sites.faces[a][0], 2 * kCells) << deg;
    }
    const auto e = measure(x, sites);
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_NEAR(e.edge[a], (2 * kCells + 1) * 0.5 * kA * (1.0 + strain[a]), bound) << deg;
    }
    EXPECT_NEAR(e.rotation_deg, deg, 0.05);
  }
}

// The sites fitted once, at the start, carry the block as it turns on.
TEST(CrystalBlock, SitesFittedAtTheStartFollowTheTurn) {
  const std::array<double, 3> strain{0.0, 0.0, 0.0};
  const auto start = placed(strain, {1.0, 1.0, 0.0}, 2.0, {50.0, 50.0, 50.0}, 0.0, 1);
  const auto sites = fit_block_sites(start, 0.5 * kA);
  const auto turned = placed(strain, {0.2, 1.0, -0.4}, 25.0, {51.0, 49.0, 52.0}, 0.0, 1);
  const auto e = measure(turned, sites);
  for (std::size_t a = 0; a < 3; ++a) EXPECT_NEAR(e.edge[a], 21 * 0.5 * kA, 1e-9);
  EXPECT_NEAR(e.volume, std::pow(21 * 0.5 * kA, 3), 1e-6);
}

// Shares summed apart (as on several ranks) give the whole block's edges.
TEST(CrystalBlock, SharesAddToTheWhole) {
  const auto x = placed({0.01, 0.0, -0.01}, {0.0, 0.0, 1.0}, 4.0, {0.0, 0.0, 0.0}, 0.1, 3);
  const auto sites = fit_block_sites(x, 0.5 * kA);
  BlockSums even, odd;
  for (std::size_t p = 0; p < x.size(); ++p) (p % 2 == 0 ? even : odd).add(sites, p, x[p]);
  for (std::size_t k = 0; k < BlockSums::kSize; ++k) even.sums[k] += odd.sums[k];
  const auto whole = measure(x, sites);
  const auto split = block_edges(sites, even);
  for (std::size_t a = 0; a < 3; ++a) EXPECT_NEAR(split.edge[a], whole.edge[a], 1e-9);
}

// A particle sitting on a face is not the face: the face is the outermost
// plane holding at least half the median plane count.
TEST(CrystalBlock, AnAdatomDoesNotStandForTheFace) {
  auto x = placed({0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 0.0, {0.0, 0.0, 0.0}, 0.0, 1);
  x.push_back({(kCells + 1) * 0.5 * kA, 0.0, 0.5 * kA});
  const auto sites = fit_block_sites(x, 0.5 * kA);
  EXPECT_EQ(sites.faces[0][1] - sites.faces[0][0], 2 * kCells);
  EXPECT_NEAR(measure(x, sites).edge[0], 21 * 0.5 * kA, 1e-9);
}

TEST(CrystalBlock, TooFewParticlesAreRefused) {
  EXPECT_THROW((void)fit_block_sites({{0, 0, 0}, {1, 1, 1}}, 3.6), pbms::Error);
}
