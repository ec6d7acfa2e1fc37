#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "pbms/error.hpp"
#include "pbms/geometry/composite_regions.hpp"
#include "pbms/geometry/lattice_fill.hpp"
#include "pbms/geometry/orientation.hpp"
#include "pbms/geometry/particle_groups.hpp"
#include "pbms/geometry/primitive_regions.hpp"
#include "pbms/geometry/region_spec.hpp"
#include "pbms/grid/cell_fill.hpp"
#include "pbms/grid/regular_grid.hpp"

using namespace pbms::geometry;
using pbms::Error;

namespace {

constexpr double kPi = std::numbers::pi;

// Runs `fn`, which must throw pbms::Error with every fragment in its message.
template <typename F>
void expect_error_mentions(F&& fn, std::initializer_list<std::string> fragments) {
  try {
    fn();
    ADD_FAILURE() << "expected pbms::Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    for (const auto& f : fragments) {
      EXPECT_NE(what.find(f), std::string::npos) << "'" << f << "' not in: " << what;
    }
  }
}

RegionPtr block(const Vec3& lo, const Vec3& hi) {
  return std::make_shared<const BlockRegion>(lo, hi);
}

bool zyx_less(const Vec3& l, const Vec3& r) {
  return std::array{l[2], l[1], l[0]} < std::array{r[2], r[1], r[0]};
}

// Strictly increasing by z, y, x: sorted and no duplicate site.
bool strictly_zyx_sorted(const std::vector<Vec3>& p) {
  return std::adjacent_find(p.begin(), p.end(), [](const Vec3& l, const Vec3& r) {
           return !zyx_less(l, r);
         }) == p.end();
}

double distance(const Vec3& a, const Vec3& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

double min_pair_distance(const std::vector<Vec3>& p) {
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) m = std::min(m, distance(p[i], p[j]));
  }
  return m;
}

// The site closest to x.
Vec3 nearest_site(const std::vector<Vec3>& p, const Vec3& x) {
  return *std::min_element(p.begin(), p.end(), [&](const Vec3& l, const Vec3& r) {
    return distance(l, x) < distance(r, x);
  });
}

int neighbours_within(const std::vector<Vec3>& p, const Vec3& x, double r) {
  int n = 0;
  for (const auto& q : p) {
    const double d = distance(q, x);
    if (d > 0.0 && d <= r) ++n;
  }
  return n;
}

RegionSpec spec(std::string style, std::map<std::string, std::vector<double>> params = {},
                std::vector<RegionSpec> children = {}) {
  return {std::move(style), std::move(params), {}, std::move(children)};
}

RegionSpec block_spec(const Vec3& lo, const Vec3& hi) {
  return spec("block", {{"lo", {lo[0], lo[1], lo[2]}}, {"hi", {hi[0], hi[1], hi[2]}}});
}

}  // namespace

// --- regions --------------------------------------------------------------

TEST(GeometryRegion, BlockIsHalfOpen) {
  const BlockRegion b({0.0, 1.0, 2.0}, {1.0, 2.0, 3.0});
  EXPECT_TRUE(b.contains({0.0, 1.0, 2.0}));
  EXPECT_TRUE(b.contains({0.5, 1.5, 2.5}));
  EXPECT_FALSE(b.contains({1.0, 1.5, 2.5}));
  EXPECT_FALSE(b.contains({0.5, 2.0, 2.5}));
  EXPECT_FALSE(b.contains({0.5, 1.5, 3.0}));
  EXPECT_FALSE(b.contains({std::nan(""), 1.5, 2.5}));
  EXPECT_EQ(b.bounds(), (Box{{0.0, 1.0, 2.0}, {1.0, 2.0, 3.0}}));
}

TEST(GeometryRegion, CurvedSurfacesAreClosedAndAxialFacesHalfOpen) {
  const SphereRegion s({1.0, 2.0, 3.0}, 2.0);
  EXPECT_TRUE(s.contains({3.0, 2.0, 3.0}));
  EXPECT_TRUE(s.contains({1.0, 2.0, 1.0}));
  EXPECT_FALSE(s.contains({3.0 + 1e-12, 2.0, 3.0}));
  EXPECT_EQ(s.bounds(), (Box{{-1.0, 0.0, 1.0}, {3.0, 4.0, 5.0}}));
  // A lattice site at the radius in exact arithmetic is inside even where
  // floating point puts it a rounding beyond (72.3 - 61.455 > 3 x 3.615).
  const double a = 3.615;
  ASSERT_GT(20 * a - 17 * a, 3 * a);
  EXPECT_TRUE(SphereRegion({17 * a, 0.0, 0.0}, 3 * a).contains({20 * a, 0.0, 0.0}));

  // Along y, so centre is (x, z).
  const CylinderRegion c(Axis::kY, {1.0, 3.0}, 0.5, 0.0, 2.0);
  EXPECT_TRUE(c.contains({1.5, 0.0, 3.0}));
  EXPECT_TRUE(c.contains({1.0, 1.0, 2.5}));
  EXPECT_FALSE(c.contains({1.0, 2.0, 3.0}));
  EXPECT_FALSE(c.contains({1.0, -1e-12, 3.0}));
  EXPECT_FALSE(c.contains({3.0, 1.0, 1.0}));  // centre swapped: a wrong axis order shows
  EXPECT_EQ(c.bounds(), (Box{{0.5, 0.0, 2.5}, {1.5, 2.0, 3.5}}));

  const CylinderRegion cx(Axis::kX, {1.0, 3.0}, 0.5, 0.0, 2.0);
  EXPECT_TRUE(cx.contains({1.0, 1.0, 3.5}));
  EXPECT_EQ(cx.bounds(), (Box{{0.0, 0.5, 2.5}, {2.0, 1.5, 3.5}}));
}

TEST(GeometryRegion, CompositesAreSetOperations) {
  const auto a = block({0, 0, 0}, {2, 2, 2});
  const auto b = block({1, 1, 1}, {3, 3, 3});
  const auto far = block({5, 5, 5}, {6, 6, 6});
  const UnionRegion u({a, b});
  const IntersectionRegion i({a, b});
  const DifferenceRegion d(a, b);
  const Vec3 only_a{0.5, 0.5, 0.5};
  const Vec3 both{1.5, 1.5, 1.5};
  const Vec3 only_b{2.5, 2.5, 2.5};
  EXPECT_TRUE(u.contains(only_a) && u.contains(both) && u.contains(only_b));
  EXPECT_TRUE(!i.contains(only_a) && i.contains(both) && !i.contains(only_b));
  EXPECT_TRUE(d.contains(only_a) && !d.contains(both) && !d.contains(only_b));

  EXPECT_EQ(u.bounds(), (Box{{0, 0, 0}, {3, 3, 3}}));
  EXPECT_EQ(i.bounds(), (Box{{1, 1, 1}, {2, 2, 2}}));
  EXPECT_EQ(d.bounds(), a->bounds());
  EXPECT_TRUE(IntersectionRegion({a, far}).bounds().empty());
  // An empty part does not stretch a union's box.
  const auto nothing = std::make_shared<const IntersectionRegion>(std::vector<RegionPtr>{a, far});
  EXPECT_EQ(UnionRegion({nothing, b}).bounds(), b->bounds());
}

TEST(GeometryRegion, InvalidShapesThrow) {
  expect_error_mentions([] { BlockRegion({0, 0, 0}, {1, 0, 1}); }, {"lo < hi", "along y"});
  expect_error_mentions([] { BlockRegion({0, 0, std::nan("")}, {1, 1, 1}); }, {"finite"});
  expect_error_mentions([] { SphereRegion({0, 0, 0}, 0.0); }, {"radius", "positive"});
  expect_error_mentions([] { CylinderRegion(Axis::kZ, {0, 0}, 1.0, 2.0, 2.0); }, {"lo < hi"});
  expect_error_mentions([] { CylinderRegion(Axis::kZ, {0, 0}, -1.0, 0.0, 2.0); }, {"radius"});
  expect_error_mentions([] { UnionRegion({}); }, {"at least one"});
  expect_error_mentions([] { DifferenceRegion(block({0, 0, 0}, {1, 1, 1}), nullptr); }, {"null"});
}

// --- crystal orientation ----------------------------------------------------

TEST(GeometryOrientation, RotatesMillerAxesOntoBoxAxes) {
  const Orientation o({1, 1, 0}, {-1, 1, 0}, {0, 0, 1});
  const Vec3 x = o.to_box({1.0 / std::sqrt(2.0), 1.0 / std::sqrt(2.0), 0.0});
  EXPECT_NEAR(x[0], 1.0, 1e-15);
  EXPECT_NEAR(x[1], 0.0, 1e-15);
  EXPECT_NEAR(x[2], 0.0, 1e-15);
  const Vec3 v{0.3, -1.7, 2.2};
  const Vec3 back = o.to_crystal(o.to_box(v));
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(back[d], v[d], 1e-14);
  EXPECT_DOUBLE_EQ(o.axis_length(0), std::sqrt(2.0));
  EXPECT_EQ(Orientation(), Orientation({1, 0, 0}, {0, 1, 0}, {0, 0, 1}));
}

TEST(GeometryOrientation, InvalidAxesThrow) {
  expect_error_mentions(
      [] {
        Orientation({1, 1, 0}, {1, 0, 0}, {0, 0, 1});
      },
      {"not orthogonal", "x [1 1 0]", "y [1 0 0]"});
  expect_error_mentions(
      [] {
        Orientation({1, 0, 0}, {0, 1, 0}, {1, 0, 1});
      },
      {"not orthogonal", "z [1 0 1]"});
  expect_error_mentions(
      [] {
        Orientation({1, 1, 0}, {1, -1, 0}, {0, 0, 1});
      },
      {"left-handed", "[0 0 -2]"});
  expect_error_mentions([] { Orientation({1, 0, 0}, {0, 0, 0}, {0, 0, 1}); }, {"along y"});
}

// --- lattice fill -------------------------------------------------------------

TEST(GeometryLattice, CommensurateBlockHoldsExactlyOneBasisPerCell) {
  const double a = 1.6;
  const Vec3 origin{0.3, -0.7, 1.1};
  const std::array<int, 3> n{5, 4, 3};
  Vec3 hi{};
  for (int d = 0; d < 3; ++d) hi[d] = origin[d] + n[d] * a;
  const BlockRegion box(origin, hi);
  EXPECT_EQ(fill_fcc(box, a, {}, origin).size(), 4u * 5 * 4 * 3);
  EXPECT_EQ(fill_sc(box, a, {}, origin).size(), 1u * 5 * 4 * 3);
  EXPECT_EQ(fill_lattice(LatticeStyle::kBcc, box, a, {}, origin).size(), 2u * 5 * 4 * 3);

  // The same block two cells further on: faces still on lattice planes.
  Vec3 lo2{};
  Vec3 hi2{};
  for (int d = 0; d < 3; ++d) {
    lo2[d] = origin[d] + 2 * a;
    hi2[d] = origin[d] + (2 + n[d]) * a;
  }
  EXPECT_EQ(fill_fcc(BlockRegion(lo2, hi2), a, {}, origin).size(), 4u * 5 * 4 * 3);
}

TEST(GeometryLattice, SitesAreOnTheFccLattice) {
  const double a = 1.3;
  const auto p = fill_fcc(BlockRegion({0, 0, 0}, {a, a, a}), a);
  const std::vector<Vec3> expected{
      {0, 0, 0}, {a / 2, a / 2, 0}, {a / 2, 0, a / 2}, {0, a / 2, a / 2}};
  ASSERT_EQ(p.size(), 4u);
  for (const auto& e : expected) {
    EXPECT_NE(std::find(p.begin(), p.end(), e), p.end()) << e[0] << " " << e[1] << " " << e[2];
  }
}

TEST(GeometryLattice, AdjacentBlocksPartitionTheSites) {
  const double a = 1.0;
  const Orientation rotated({1, 1, 0}, {-1, 1, 0}, {0, 0, 1});
  for (const auto& orient : {Orientation(), rotated}) {
    // Cuts exactly on lattice planes, where a site lies on the shared face.
    Vec3 cut{};
    for (int d = 0; d < 3; ++d) cut[d] = 7.0 * (a / (2.0 * orient.axis_length(d)));
    const Vec3 lo{-0.2, -0.1, -0.3};
    const Vec3 hi{6.1, 5.3, 5.9};
    const auto whole = fill_fcc(BlockRegion(lo, hi), a, orient);
    ASSERT_GT(whole.size(), 500u);
    EXPECT_TRUE(std::any_of(whole.begin(), whole.end(), [&](const Vec3& x) {
      return x[0] == cut[0] || x[1] == cut[1] || x[2] == cut[2];
    }));

    std::vector<Vec3> pieces;
    for (int octant = 0; octant < 8; ++octant) {
      Vec3 plo{};
      Vec3 phi{};
      for (int d = 0; d < 3; ++d) {
        const bool upper = (octant >> d) & 1;
        plo[d] = upper ? cut[d] : lo[d];
        phi[d] = upper ? hi[d] : cut[d];
      }
      const auto part = fill_fcc(BlockRegion(plo, phi), a, orient);
      pieces.insert(pieces.end(), part.begin(), part.end());
    }
    EXPECT_EQ(pieces.size(), whole.size());
    std::sort(pieces.begin(), pieces.end(), zyx_less);
    EXPECT_TRUE(strictly_zyx_sorted(pieces)) << "a site is in two pieces";
    EXPECT_EQ(pieces, whole);
  }
}

TEST(GeometryLattice, SphereCountMatchesTheNumberDensity) {
  const double a = 1.0;
  const double r = 10.3;
  const auto p = fill_fcc(SphereRegion({0.21, 0.37, 0.13}, r), a);
  const double expected = 4.0 / 3.0 * kPi * r * r * r * 4.0 / (a * a * a);
  EXPECT_NEAR(static_cast<double>(p.size()) / expected, 1.0, 0.02);
}

TEST(GeometryLattice, SphereCentredOnASiteKeepsWholeShells) {
  // 1 + 12 first neighbours (a/sqrt2) + 6 second neighbours (a, on the surface).
  EXPECT_EQ(fill_fcc(SphereRegion({0, 0, 0}, 2.0), 2.0).size(), 19u);
  EXPECT_EQ(fill_sc(SphereRegion({0, 0, 0}, 1.0), 1.0).size(), 7u);
}

TEST(GeometryLattice, RotatedFccHasTheFccDensityAndNeighbourDistance) {
  const double a = 1.7;
  const std::vector<Orientation> orientations{
      Orientation({1, 1, 0}, {-1, 1, 0}, {0, 0, 1}),
      Orientation({1, 1, -2}, {1, 1, 1}, {1, -1, 0}),
  };
  std::mt19937_64 rng(20240611);
  for (const auto& orient : orientations) {
    // One box's count moves by a few per cent with where whole lattice planes
    // fall at its faces. Over box positions uniform across a lattice period
    // along each axis (a |axis|, a lattice translation) the mean count is
    // exactly 4 V / a^3, so the mean of a few dozen boxes tests the density.
    const Vec3 size{12.3 * a, 11.1 * a, 10.7 * a};
    const int boxes = 48;
    double count = 0.0;
    for (int s = 0; s < boxes; ++s) {
      Vec3 lo{};
      Vec3 hi{};
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::uniform_real_distribution<double>(0.0, a * orient.axis_length(d))(rng);
        hi[d] = lo[d] + size[d];
      }
      const auto p = fill_fcc(BlockRegion(lo, hi), a, orient);
      EXPECT_TRUE(strictly_zyx_sorted(p));
      count += static_cast<double>(p.size()) / boxes;
    }
    const double volume = size[0] * size[1] * size[2];
    EXPECT_NEAR(count / (4.0 * volume / (a * a * a)), 1.0, 0.02);

    const auto sample = fill_fcc(BlockRegion({0, 0, 0}, {2.5 * a, 2.5 * a, 2.5 * a}), a, orient);
    ASSERT_GT(sample.size(), 30u);
    EXPECT_NEAR(min_pair_distance(sample), a / std::sqrt(2.0), 1e-12);
    // An interior site has 12 first and 6 second neighbours.
    const auto p = fill_fcc(BlockRegion({0, 0, 0}, size), a, orient);
    const Vec3 centre = nearest_site(p, {size[0] / 2, size[1] / 2, size[2] / 2});
    EXPECT_EQ(neighbours_within(p, centre, 1.01 * a / std::sqrt(2.0)), 12);
    EXPECT_EQ(neighbours_within(p, centre, 1.01 * a), 18);
  }
}

TEST(GeometryLattice, RotatedCommensurateBoxIsExactAwayFromPlanes) {
  // Periods of this orientation: a sqrt2 along x and y, a along z. With the
  // origin half a plane spacing off every face no site is on a face.
  const double a = 1.0;
  const Orientation orient({1, 1, 0}, {-1, 1, 0}, {0, 0, 1});
  const int nx = 4;
  const int ny = 3;
  const int nz = 5;
  const Vec3 hi{nx * a * std::sqrt(2.0), ny * a * std::sqrt(2.0), nz * a};
  Vec3 origin{};
  for (int d = 0; d < 3; ++d) origin[d] = 0.5 * a / (2.0 * orient.axis_length(d));
  EXPECT_EQ(fill_fcc(BlockRegion({0, 0, 0}, hi), a, orient, origin).size(), 8u * nx * ny * nz);
}

TEST(GeometryLattice, OrderIsByZYXAndReproducible) {
  const SphereRegion s({0.5, 0.25, 0.125}, 3.2);
  const auto p = fill_fcc(s, 1.1);
  EXPECT_TRUE(strictly_zyx_sorted(p));
  EXPECT_EQ(p, fill_fcc(s, 1.1));
}

TEST(GeometryLattice, BadInputsThrow) {
  const BlockRegion b({0, 0, 0}, {10, 10, 10});
  expect_error_mentions([&] { (void)fill_fcc(b, 0.0); }, {"lattice constant", "positive"});
  expect_error_mentions([&] { (void)fill_fcc(b, std::nan("")); }, {"lattice constant"});
  expect_error_mentions([&] { (void)fill_fcc(b, 1e-5); }, {"units"});
  expect_error_mentions([&] { (void)fill_fcc(b, 1.0, {}, {0, std::nan(""), 0}); }, {"origin"});
  EXPECT_EQ(lattice_style_from_name("bcc"), LatticeStyle::kBcc);
  EXPECT_EQ(sites_per_cell(lattice_style_from_name("fcc")), 4);
  expect_error_mentions([] { (void)lattice_style_from_name("hcp"); }, {"'hcp'", "sc, bcc, fcc"});
}

// --- composite fills ------------------------------------------------------------

TEST(GeometryLattice, UnionIntersectionAndDifferenceCounts) {
  const auto a = block({0, 0, 0}, {6, 6, 6});
  const auto b = block({4, 0, 0}, {10, 6, 6});
  const std::size_t na = fill_fcc(*a, 1.0).size();
  const std::size_t nb = fill_fcc(*b, 1.0).size();
  const std::size_t n_union = fill_fcc(UnionRegion({a, b}), 1.0).size();
  const std::size_t n_both = fill_fcc(IntersectionRegion({a, b}), 1.0).size();
  EXPECT_EQ(n_union, 4u * 10 * 6 * 6);
  EXPECT_EQ(n_both, 4u * 2 * 6 * 6);
  EXPECT_EQ(n_union, na + nb - n_both);

  const auto slab = block({0, 0, 0}, {10, 10, 10});
  const auto hole = std::make_shared<const SphereRegion>(Vec3{5.1, 4.9, 5.2}, 3.0);
  const std::size_t n_hole = fill_fcc(*hole, 1.0).size();
  EXPECT_GT(n_hole, 0u);
  EXPECT_EQ(fill_fcc(DifferenceRegion(slab, hole), 1.0).size(), 4u * 1000 - n_hole);
}

// --- material points -------------------------------------------------------------

TEST(GeometryCells, CellAlignedBlockGetsEveryPointAndItsVolume) {
  const pbms::grid::RegularGrid g({-1.3, 2.1, 0.7}, 0.37, {7, 5, 6});
  const double h = g.cell_size();
  Vec3 lo{};
  Vec3 hi{};
  const std::array<int, 3> c_lo{2, 1, 0};
  const std::array<int, 3> c_hi{5, 4, 6};
  for (int d = 0; d < 3; ++d) {
    lo[d] = g.origin()[d] + c_lo[d] * h;
    hi[d] = g.origin()[d] + c_hi[d] * h;
  }
  const BlockRegion b(lo, hi);
  for (int n = 1; n <= 3; ++n) {
    const auto mp = fill_cells(b, g, n);
    ASSERT_EQ(mp.positions.size(), std::size_t{3 * 3 * 6} * n * n * n);
    ASSERT_EQ(mp.volumes.size(), mp.positions.size());
    double v = 0.0;
    for (const double pv : mp.volumes) v += pv;
    EXPECT_NEAR(v / (3 * 3 * 6 * h * h * h), 1.0, 1e-12);
    EXPECT_TRUE(strictly_zyx_sorted(mp.positions));
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(mp.positions.front()[d], lo[d] + 0.5 * h / n, 1e-12);
    EXPECT_DOUBLE_EQ(mp.volumes.front(), std::pow(h / n, 3));
  }
}

TEST(GeometryCells, OnlyGridCellsAreFilled) {
  const pbms::grid::RegularGrid g({0, 0, 0}, 0.5, {4, 3, 2});
  const auto mp = fill_cells(BlockRegion({-10, -10, -10}, {10, 10, 10}), g, 2);
  EXPECT_EQ(mp.positions.size(), std::size_t{4 * 3 * 2 * 8});
  for (const auto& x : mp.positions) EXPECT_TRUE(g.contains(x));
  EXPECT_TRUE(fill_cells(BlockRegion({5, 5, 5}, {6, 6, 6}), g, 2).positions.empty());
}

TEST(GeometryCells, SphereVolumeConverges) {
  const pbms::grid::RegularGrid g({0, 0, 0}, 0.37, {8, 8, 8});
  const double r = 1.1;
  const auto mp = fill_cells(SphereRegion({1.43, 1.51, 1.47}, r), g, 8);
  double v = 0.0;
  for (const double pv : mp.volumes) v += pv;
  EXPECT_NEAR(v / (4.0 / 3.0 * kPi * r * r * r), 1.0, 0.02);
  expect_error_mentions(
      [&] {
        (void)fill_cells(SphereRegion({1, 1, 1}, 1), g, 0);
      },
      {"at least 1", "got 0"});
}

// --- groups ------------------------------------------------------------------------

TEST(GeometryGroups, RegionGroupsAndSetOperations) {
  const auto positions = fill_sc(BlockRegion({0, 0, 0}, {4, 4, 4}), 1.0);  // 64 sites
  ParticleGroups groups;
  groups.add_region_group("left", positions, BlockRegion({0, 0, 0}, {2, 4, 4}));
  groups.add_region_group("bottom", positions, BlockRegion({0, 0, 0}, {4, 4, 1}));
  groups.add_union("left_or_bottom", "left", "bottom");
  groups.add_intersection("left_and_bottom", "left", "bottom");
  groups.add_difference("left_not_bottom", "left", "bottom");

  EXPECT_EQ(groups.members("left").size(), 32u);
  EXPECT_EQ(groups.members("bottom").size(), 16u);
  EXPECT_EQ(groups.members("left_and_bottom").size(), 8u);
  EXPECT_EQ(groups.members("left_or_bottom").size(), 32u + 16u - 8u);
  EXPECT_EQ(groups.members("left_not_bottom").size(), 24u);
  for (const auto i : groups.members("left_not_bottom")) {
    EXPECT_LT(positions[i][0], 2.0);
    EXPECT_GE(positions[i][2], 1.0);
  }
  for (const auto& name : groups.names()) {
    const auto& m = groups.members(name);
    EXPECT_TRUE(std::adjacent_find(m.begin(), m.end(), std::greater_equal<>()) == m.end()) << name;
  }
  EXPECT_EQ(groups.names(), (std::vector<std::string>{"bottom", "left", "left_and_bottom",
                                                      "left_not_bottom", "left_or_bottom"}));
}

TEST(GeometryGroups, ExplicitMembersAreNormalisedAndMistakesThrow) {
  ParticleGroups groups;
  expect_error_mentions([&] { (void)groups.members("grip"); }, {"'grip'", "none"});
  groups.add("grip", {5, 1, 3, 1});
  EXPECT_EQ(groups.members("grip"), (ParticleGroups::Members{1, 3, 5}));
  groups.add("empty", {});
  EXPECT_TRUE(groups.members("empty").empty());
  expect_error_mentions([&] { (void)groups.members("gauge"); }, {"'gauge'", "empty, grip"});
  expect_error_mentions([&] { groups.add_union("u", "grip", "gauge"); }, {"'gauge'"});
  expect_error_mentions([&] { groups.add("grip", {1}); }, {"'grip'", "already"});
  expect_error_mentions([&] { groups.add("bad", {2, -1}); }, {"negative", "-1"});
  expect_error_mentions([&] { groups.add("", {1}); }, {"name"});
  EXPECT_FALSE(groups.contains("u"));
  EXPECT_EQ(groups.size(), 2u);
}

// --- region specs ----------------------------------------------------------------

TEST(GeometryRegionSpec, BuildsEveryStyle) {
  const auto names = RegionRegistry::names();
  for (const auto* style : {"block", "cylinder", "difference", "intersection", "sphere", "union"}) {
    EXPECT_TRUE(std::binary_search(names.begin(), names.end(), style)) << style;
  }
  const auto b = RegionRegistry::create(block_spec({0, 0, 0}, {2, 2, 2}));
  EXPECT_TRUE(b->contains({0, 0, 0}));
  EXPECT_FALSE(b->contains({2, 1, 1}));

  const auto sphere = spec("sphere", {{"centre", {1, 1, 1}}, {"radius", {0.5}}});
  EXPECT_TRUE(RegionRegistry::create(sphere)->contains({1.5, 1, 1}));

  RegionSpec cyl =
      spec("cylinder", {{"centre", {1, 3}}, {"radius", {0.5}}, {"lo", {0}}, {"hi", {2}}});
  cyl.words["axis"] = "y";
  const auto c = RegionRegistry::create(cyl);
  EXPECT_TRUE(c->contains({1.5, 1.0, 3.0}));
  EXPECT_FALSE(c->contains({1.0, 2.0, 3.0}));

  const auto u = RegionRegistry::create(
      spec("union", {}, {block_spec({0, 0, 0}, {1, 1, 1}), block_spec({2, 0, 0}, {3, 1, 1})}));
  EXPECT_TRUE(u->contains({2.5, 0.5, 0.5}));
  EXPECT_FALSE(u->contains({1.5, 0.5, 0.5}));

  const auto i = RegionRegistry::create(spec(
      "intersection", {}, {block_spec({0, 0, 0}, {2, 2, 2}), block_spec({1, 1, 1}, {3, 3, 3})}));
  EXPECT_TRUE(i->contains({1.5, 1.5, 1.5}));
  EXPECT_FALSE(i->contains({0.5, 0.5, 0.5}));

  // First minus all the others.
  const auto d = RegionRegistry::create(
      spec("difference", {},
           {block_spec({0, 0, 0}, {3, 1, 1}), block_spec({0, 0, 0}, {1, 1, 1}),
            spec("sphere", {{"centre", {2.5, 0.5, 0.5}}, {"radius", {0.1}}})}));
  EXPECT_FALSE(d->contains({0.5, 0.5, 0.5}));
  EXPECT_TRUE(d->contains({1.5, 0.5, 0.5}));
  EXPECT_FALSE(d->contains({2.5, 0.5, 0.5}));
  EXPECT_TRUE(d->contains({2.9, 0.5, 0.5}));
}

TEST(GeometryRegionSpec, ErrorsNameTheProblem) {
  const auto create = [](const RegionSpec& s) { return [s] { (void)RegionRegistry::create(s); }; };
  expect_error_mentions(create(spec("block", {{"lo", {0, 0, 0}}})),
                        {"region 'block'", "missing parameter 'hi'", "lo[3], hi[3]"});
  expect_error_mentions(
      create(spec("block", {{"lo", {0, 0, 0}}, {"hi", {1, 1, 1}}, {"radius", {1}}})),
      {"region 'block'", "unknown parameter 'radius'"});
  expect_error_mentions(create(spec("sphere", {{"centre", {0, 0}}, {"radius", {1}}})),
                        {"'centre' needs 3 numbers, got 2"});
  expect_error_mentions(create(spec("sphere", {{"centre", {0, 0, 0}}, {"radius", {-1}}})),
                        {"region 'sphere'", "radius must be a positive number, got -1"});
  expect_error_mentions(create(spec("blok")), {"unknown region style 'blok'", "block, cylinder"});

  RegionSpec cyl =
      spec("cylinder", {{"centre", {1, 3}}, {"radius", {0.5}}, {"lo", {0}}, {"hi", {2}}});
  cyl.words["axis"] = "w";
  expect_error_mentions(create(cyl), {"region 'cylinder'", "x, y or z", "'w'"});
  cyl.words.clear();
  expect_error_mentions(create(cyl), {"missing parameter 'axis'"});
  cyl.params["axis"] = {2};
  expect_error_mentions(create(cyl), {"'axis' must be a word"});

  expect_error_mentions(create(spec("union", {}, {block_spec({0, 0, 0}, {1, 1, 1})})),
                        {"region 'union'", "at least two", "got 1"});
  expect_error_mentions(
      create(spec("union", {{"lo", {0, 0, 0}}},
                  {block_spec({0, 0, 0}, {1, 1, 1}), block_spec({0, 0, 0}, {1, 1, 1})})),
      {"takes no parameters", "'lo'"});
  expect_error_mentions(create(spec("block", {{"lo", {0, 0, 0}}, {"hi", {1, 1, 1}}},
                                    {block_spec({0, 0, 0}, {1, 1, 1})})),
                        {"takes no child regions"});
  expect_error_mentions(
      create(spec("difference", {},
                  {block_spec({0, 0, 0}, {1, 1, 1}), spec("sphere", {{"centre", {0, 0, 0}}})})),
      {"region 'difference': children[1]: region 'sphere': missing parameter 'radius'"});
}

TEST(GeometryRegionSpec, NewStylesCanBeRegistered) {
  // As a plugin would: a style defined outside region_spec.cpp.
  RegionRegistry::add("test_positive_octant", [](const RegionSpec&) -> std::unique_ptr<Region> {
    return std::make_unique<BlockRegion>(Vec3{0, 0, 0}, Vec3{1e3, 1e3, 1e3});
  });
  EXPECT_TRUE(RegionRegistry::contains("test_positive_octant"));
  EXPECT_TRUE(RegionRegistry::create(spec("test_positive_octant"))->contains({1, 1, 1}));
  expect_error_mentions(
      [] { RegionRegistry::add("block", [](const RegionSpec&) { return nullptr; }); },
      {"'block'", "already"});
}
