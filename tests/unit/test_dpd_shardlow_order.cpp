// The Shardlow sweep order (kernels/shardlow_pair_order.hpp): every pair
// once, colours whose cells share no particle, and the same sequence per
// cell whether one process sweeps the box or two sub-boxes with ghosts do.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "kernels/fcc_crystal.hpp"
#include "kernels/shardlow_pair_order.hpp"

using namespace pbms::dpd;

namespace {

constexpr double kCutoff = 10.0;  // Å

using IdPair = std::pair<std::int64_t, std::int64_t>;
using Cell = std::array<int, 3>;

// Particles at random in the box: a disordered state. The tests pair it with
// an fcc lattice (fcc_crystal), whose planes would fall on the faces of an
// unshifted grid: the hard case.
DpdParticles random_particles(const OrthogonalBox& box, int n, unsigned seed) {
  DpdParticles p;
  p.mass_per_type = {1.0};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < n; ++k) {
    Vec3 x{};
    for (int a = 0; a < 3; ++a) x[a] = box.lo[a] + box.length(a) * u(rng);
    p.add(1000 + 7 * k, 0, x);  // ids not in index order
  }
  return p;
}

std::set<IdPair> brute_force_pairs(const DpdParticles& p, const OrthogonalBox& box) {
  std::set<IdPair> out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const Vec3 d =
          box.minimum_image({p.x[i][0] - p.x[j][0], p.x[i][1] - p.x[j][1], p.x[i][2] - p.x[j][2]});
      if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < kCutoff * kCutoff) {
        out.insert(std::minmax(p.id[i], p.id[j]));
      }
    }
  }
  return out;
}

// Per colour and cell, the sequence of id pairs a sweep takes.
using Sequence = std::map<std::tuple<int, Cell>, std::vector<IdPair>>;

Sequence sequence_of(const ShardlowPairOrder& order, const DpdParticles& p) {
  Sequence s;
  for (int c = 0; c < ShardlowPairOrder::kColours; ++c) {
    for (const ShardlowPair& q : order.colour(c)) {
      // The same cell seen through a periodic image: fold it back.
      Cell cell = q.cell;
      for (int a = 0; a < 3; ++a) {
        const int n = order.cells()[a];
        cell[a] = ((cell[a] % n) + n) % n;
      }
      s[{c, cell}].push_back({p.id[q.i], p.id[q.j]});
    }
  }
  return s;
}

void expect_a_valid_order(const ShardlowPairOrder& order, const DpdParticles& p,
                          const OrthogonalBox& box) {
  std::set<IdPair> seen;
  for (int c = 0; c < ShardlowPairOrder::kColours; ++c) {
    std::map<std::size_t, Cell> cell_of_particle;
    IdPair previous{-1, -1};
    Cell previous_cell{-1, -1, -1};
    for (const ShardlowPair& q : order.colour(c)) {
      const IdPair ids{p.id[q.i], p.id[q.j]};
      ASSERT_LT(ids.first, ids.second);
      EXPECT_TRUE(seen.insert(ids).second) << "pair swept twice";
      if (q.cell == previous_cell) {
        EXPECT_LT(previous, ids) << "cell not in id order";
      }
      previous = ids;
      previous_cell = q.cell;
      for (const std::size_t k : {q.i, q.j}) {
        const auto [it, fresh] = cell_of_particle.emplace(k, q.cell);
        EXPECT_TRUE(fresh || it->second == q.cell) << "colour " << c << ": a particle in two cells";
      }
    }
  }
  EXPECT_EQ(seen, brute_force_pairs(p, box));
}

}  // namespace

TEST(ShardlowPairOrder, EveryPairOnceAndCellsOfAColourShareNoParticle) {
  OrthogonalBox box;
  box.lo = {-3.0, 0.0, 1.0};
  box.hi = {47.0, 38.0, 52.0};
  box.periodic = {true, true, false};
  const DpdParticles p = random_particles(box, 900, 3);
  ShardlowPairOrder order(box, kCutoff, 0.0);
  for (int a = 0; a < 3; ++a) {
    EXPECT_GT(order.cell_width()[a], 0.5 * kCutoff);  // the reach, with no skin
    if (box.periodic[a]) {
      EXPECT_EQ(order.cells()[a] % 3, 0);
    }
  }
  order.build(p, box, [](const Vec3&) { return true; });
  expect_a_valid_order(order, p, box);

  const FccCrystal crystal = fcc_crystal(6, 6, 6, 7.23, 1.0);
  ShardlowPairOrder lattice(crystal.box, kCutoff, 0.0);
  lattice.build(crystal.particles, crystal.box, [](const Vec3&) { return true; });
  expect_a_valid_order(lattice, crystal.particles, crystal.box);
}

// Two sub-boxes split along x, each with the ghosts a decomposed run gives
// it (copies within the reach, at their periodic images) and its list box
// periodic in y and z only. Together they must sweep what one process does,
// cell by cell in the same order.
TEST(ShardlowPairOrder, TwoSubBoxesWithGhostsSweepLikeOneBox) {
  OrthogonalBox box;
  box.hi = {57.84, 43.38, 43.38};
  // As a decomposed run lists them: pairs within cutoff + skin, ghosts
  // within that reach of the sub-box.
  const double skin = 1.0;
  const double reach = kCutoff + skin;
  for (const bool lattice : {false, true}) {
    DpdParticles all = random_particles(box, 800, 11);
    if (lattice) {
      const FccCrystal crystal = fcc_crystal(8, 6, 6, 7.23, 1.0);
      all = crystal.particles;
      box = crystal.box;
    }
    ShardlowPairOrder serial(box, kCutoff, skin);
    serial.build(all, box, [](const Vec3&) { return true; });
    const Vec3 length{box.length(0), box.length(1), box.length(2)};
    const Sequence expected = sequence_of(serial, all);

    Sequence split;
    const double half = box.lo[0] + 0.5 * box.length(0);
    for (const auto& [lo, hi] : {std::pair{box.lo[0], half}, std::pair{half, box.hi[0]}}) {
      DpdParticles local;
      local.mass_per_type = all.mass_per_type;
      for (std::size_t i = 0; i < all.size(); ++i) {
        if (all.x[i][0] >= lo && all.x[i][0] < hi) local.add(all.id[i], 0, all.x[i]);
      }
      for (std::size_t i = 0; i < all.size(); ++i) {
        for (const double shift : {-length[0], 0.0, length[0]}) {
          Vec3 x = all.x[i];
          x[0] += shift;
          const bool inside = x[0] >= lo && x[0] < hi;
          if (!inside && x[0] >= lo - reach && x[0] < hi + reach) local.add(all.id[i], 0, x);
        }
      }
      OrthogonalBox list_box = box;
      list_box.periodic[0] = false;
      ShardlowPairOrder part(box, kCutoff, skin);
      part.build(local, list_box, [&](const Vec3& c) { return c[0] >= lo && c[0] < hi; });
      for (auto& [key, pairs] : sequence_of(part, local)) {
        auto& to = split[key];
        EXPECT_TRUE(to.empty()) << "a cell swept by both halves";
        to.insert(to.end(), pairs.begin(), pairs.end());
      }
    }
    EXPECT_EQ(split, expected) << (lattice ? "lattice" : "random");
  }
}
