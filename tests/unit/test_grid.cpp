#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "pbms/error.hpp"
#include "pbms/grid/ddmp_gradient.hpp"
#include "pbms/grid/regular_grid.hpp"
#include "pbms/grid/shape_function.hpp"
#include "pbms/grid/shape_function_linear.hpp"

using namespace pbms::grid;
using Vec3 = std::array<double, 3>;

namespace {

// Deliberately off-origin, non-unit and anisotropic in cell counts, so that
// index and offset mistakes show.
RegularGrid test_grid() {
  return RegularGrid({-1.3, 2.1, 0.7}, 0.37, {7, 5, 6});
}

Vec3 random_point_in(const RegularGrid& g, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Vec3 x{};
  for (int d = 0; d < 3; ++d) x[d] = g.origin()[d] + u(rng) * (g.upper()[d] - g.origin()[d]);
  return x;
}

// ppc^3 points per cell on a regular sub-lattice of the cells [lo, hi).
std::vector<Vec3> lattice_points(const RegularGrid& g, std::array<int, 3> lo, std::array<int, 3> hi,
                                 int ppc, Vec3 shift = {}) {
  std::vector<Vec3> pts;
  const double s = g.cell_size() / ppc;
  for (int k = lo[2] * ppc; k < hi[2] * ppc; ++k)
    for (int j = lo[1] * ppc; j < hi[1] * ppc; ++j)
      for (int i = lo[0] * ppc; i < hi[0] * ppc; ++i) {
        const std::array<int, 3> n{i, j, k};
        Vec3 x{};
        for (int d = 0; d < 3; ++d) x[d] = g.origin()[d] + (n[d] + 0.5) * s + shift[d];
        pts.push_back(x);
      }
  return pts;
}

std::vector<ShapeStencil> stencils_at(const RegularGrid& g, const ShapeFunction& sf,
                                      const std::vector<Vec3>& pts) {
  std::vector<ShapeStencil> st(pts.size());
  for (std::size_t p = 0; p < pts.size(); ++p) sf.evaluate(g, pts[p], st[p]);
  return st;
}

// Largest deviation of sum_i dN_i from 0 and of sum_i X_i (x) dN_i from I.
template <class NodeRange, class GradRange>
std::pair<double, double> completeness_error(const RegularGrid& g, const NodeRange& nodes,
                                             const GradRange& grads, std::size_t n) {
  Vec3 sum{};
  std::array<Vec3, 3> m{};
  for (std::size_t q = 0; q < n; ++q) {
    const Vec3 xi = g.node_position(nodes[q]);
    for (int a = 0; a < 3; ++a) {
      sum[a] += grads[q][a];
      for (int b = 0; b < 3; ++b) m[a][b] += xi[a] * grads[q][b];
    }
  }
  double e0 = 0.0, e1 = 0.0;
  for (int a = 0; a < 3; ++a) {
    e0 = std::max(e0, std::abs(sum[a]));
    for (int b = 0; b < 3; ++b) e1 = std::max(e1, std::abs(m[a][b] - (a == b ? 1.0 : 0.0)));
  }
  return {e0, e1};
}

}  // namespace

// ---------------------------------------------------------------- grid

TEST(RegularGrid, RejectsBadGeometry) {
  EXPECT_THROW(RegularGrid({0, 0, 0}, 0.0, {1, 1, 1}), pbms::Error);
  EXPECT_THROW(RegularGrid({0, 0, 0}, -1.0, {1, 1, 1}), pbms::Error);
  EXPECT_THROW(RegularGrid({0, 0, 0}, std::nan(""), {1, 1, 1}), pbms::Error);
  EXPECT_THROW(RegularGrid({0, 0, 0}, 1.0, {1, 0, 1}), pbms::Error);
}

TEST(RegularGrid, NodeIndexingIsXFastestAndRoundTrips) {
  const auto g = test_grid();
  EXPECT_EQ(g.nodes_per_axis(), (std::array<int, 3>{8, 6, 7}));
  EXPECT_EQ(g.node_count(), 8 * 6 * 7);
  EXPECT_EQ(g.cell_count(), 7 * 5 * 6);
  EXPECT_EQ(g.node_index({1, 0, 0}), 1);
  EXPECT_EQ(g.node_index({0, 1, 0}), 8);
  EXPECT_EQ(g.node_index({0, 0, 1}), 48);
  for (std::int64_t n = 0; n < g.node_count(); ++n) {
    ASSERT_EQ(g.node_index(g.node_ijk(n)), n);
  }
  const Vec3 x = g.node_position({3, 2, 5});
  EXPECT_DOUBLE_EQ(x[0], -1.3 + 3 * 0.37);
  EXPECT_DOUBLE_EQ(x[1], 2.1 + 2 * 0.37);
  EXPECT_DOUBLE_EQ(x[2], 0.7 + 5 * 0.37);
  EXPECT_EQ(g.node_position(g.node_index({3, 2, 5})), x);
}

TEST(RegularGrid, CellOfAndContains) {
  const RegularGrid g({0, 0, 0}, 0.5, {4, 3, 2});
  EXPECT_EQ(g.cell_of({0.6, 0.1, 0.9}), (std::array<int, 3>{1, 0, 1}));
  // A point on an inner face belongs to the upper cell.
  EXPECT_EQ(g.cell_of({1.0, 0.5, 0.0}), (std::array<int, 3>{2, 1, 0}));
  // The grid is closed: the upper faces and corner are inside, in the last cell.
  EXPECT_TRUE(g.contains(g.upper()));
  EXPECT_EQ(g.cell_of(g.upper()), (std::array<int, 3>{3, 2, 1}));
  EXPECT_EQ(g.cell_of({2.0, 0.2, 0.2}), (std::array<int, 3>{3, 0, 0}));
  // Anything beyond is outside.
  const double above = std::nextafter(2.0, 3.0);
  EXPECT_FALSE(g.contains({above, 0.2, 0.2}));
  EXPECT_FALSE(g.cell_of({above, 0.2, 0.2}).has_value());
  EXPECT_FALSE(g.cell_of({0.2, -1e-300, 0.2}).has_value());
  EXPECT_FALSE(g.contains({0.2, std::nan(""), 0.2}));
  EXPECT_EQ(g.cell_index({3, 2, 1}), g.cell_count() - 1);
}

TEST(NodeBox, LocalIndexingGhostLayersAndClipping) {
  const NodeBox own{{2, 0, 3}, {5, 4, 6}};
  EXPECT_EQ(own.extent(), (std::array<int, 3>{3, 4, 3}));
  EXPECT_EQ(own.count(), 36);
  EXPECT_TRUE(own.contains({2, 0, 3}));
  EXPECT_FALSE(own.contains({5, 0, 3}));
  EXPECT_EQ(own.local_index({2, 0, 3}), 0);
  EXPECT_EQ(own.local_index({3, 0, 3}), 1);
  EXPECT_EQ(own.local_index({2, 1, 3}), 3);
  for (std::int64_t l = 0; l < own.count(); ++l) ASSERT_EQ(own.local_index(own.ijk_of_local(l)), l);

  const auto g = test_grid();
  const NodeBox ghosted = own.grown(2).intersected(g.node_box());
  EXPECT_EQ(ghosted, (NodeBox{{0, 0, 1}, {7, 6, 7}}));
  EXPECT_EQ(g.node_box().local_index({3, 2, 5}), g.node_index({3, 2, 5}));
  EXPECT_TRUE(own.intersected(NodeBox{{6, 0, 0}, {8, 8, 8}}).empty());
}

// ---------------------------------------------------------------- linear

TEST(ShapeFunctionLinear, PartitionOfUnityCompletenessAndBounds) {
  const auto g = test_grid();
  const ShapeFunctionLinear sf;
  std::mt19937_64 rng(42);
  ShapeStencil st;
  double worst_sum = 0.0, worst_grad = 0.0, worst_moment = 0.0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 x = random_point_in(g, rng);
    sf.evaluate(g, x, st);
    ASSERT_EQ(st.count, 8);
    const auto cell = g.cell_of(x);
    ASSERT_TRUE(cell.has_value());
    double sum = 0.0;
    for (int q = 0; q < st.count; ++q) {
      ASSERT_GE(st.node[q], 0);
      ASSERT_LT(st.node[q], g.node_count());
      const auto ijk = g.node_ijk(st.node[q]);
      for (int d = 0; d < 3; ++d) {
        ASSERT_TRUE(ijk[d] == (*cell)[d] || ijk[d] == (*cell)[d] + 1);
      }
      ASSERT_GE(st.N[q], 0.0);
      ASSERT_LE(st.N[q], 1.0);
      sum += st.N[q];
    }
    worst_sum = std::max(worst_sum, std::abs(sum - 1.0));
    const auto [e0, e1] = completeness_error(g, st.node, st.dN, 8);
    worst_grad = std::max(worst_grad, e0);
    worst_moment = std::max(worst_moment, e1);
  }
  EXPECT_LT(worst_sum, 1e-14);
  EXPECT_LT(worst_grad, 1e-12);
  EXPECT_LT(worst_moment, 1e-12);
}

TEST(ShapeFunctionLinear, GradientIsTheDerivativeOfN) {
  const auto g = test_grid();
  const ShapeFunctionLinear sf;
  std::mt19937_64 rng(7);
  ShapeStencil st, sp, sm;
  const double eps = 1e-6;
  for (int trial = 0; trial < 500; ++trial) {
    // Stay away from faces so the difference quotient does not straddle one.
    auto cell = g.cell_of(random_point_in(g, rng)).value();
    std::uniform_real_distribution<double> u(0.1, 0.9);
    Vec3 x{};
    for (int d = 0; d < 3; ++d) x[d] = g.origin()[d] + (cell[d] + u(rng)) * g.cell_size();
    sf.evaluate(g, x, st);
    for (int d = 0; d < 3; ++d) {
      Vec3 xp = x, xm = x;
      xp[d] += eps;
      xm[d] -= eps;
      sf.evaluate(g, xp, sp);
      sf.evaluate(g, xm, sm);
      for (int q = 0; q < 8; ++q) {
        ASSERT_EQ(sp.node[q], st.node[q]);
        EXPECT_NEAR(st.dN[q][d], (sp.N[q] - sm.N[q]) / (2 * eps), 1e-7);
      }
    }
  }
}

TEST(ShapeFunctionLinear, InterpolatesNodes) {
  const auto g = test_grid();
  const ShapeFunctionLinear sf;
  ShapeStencil st;
  const std::int64_t n = g.node_index({3, 2, 4});
  sf.evaluate(g, g.node_position(n), st);
  for (int q = 0; q < st.count; ++q) {
    EXPECT_NEAR(st.N[q], st.node[q] == n ? 1.0 : 0.0, 1e-14);
  }
}

TEST(ShapeFunctionLinear, UpperBoundaryFaceUsesTheLastCell) {
  const auto g = test_grid();
  const ShapeFunctionLinear sf;
  std::mt19937_64 rng(3);
  ShapeStencil st;
  const int last = g.cells()[0];
  for (int trial = 0; trial < 200; ++trial) {
    Vec3 x = random_point_in(g, rng);
    x[0] = g.upper()[0];
    sf.evaluate(g, x, st);
    ASSERT_EQ(st.count, 8);
    double sum = 0.0, on_face = 0.0;
    for (int q = 0; q < st.count; ++q) {
      ASSERT_LT(st.node[q], g.node_count());
      sum += st.N[q];
      if (g.node_ijk(st.node[q])[0] == last) on_face += st.N[q];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_NEAR(on_face, 1.0, 1e-14);  // the far-wall nodes carry all weight
    const auto [e0, e1] = completeness_error(g, st.node, st.dN, 8);
    EXPECT_LT(e0, 1e-12);
    EXPECT_LT(e1, 1e-12);
  }
  // The far corner is the last node, exactly.
  sf.evaluate(g, g.upper(), st);
  for (int q = 0; q < st.count; ++q) {
    EXPECT_NEAR(st.N[q], st.node[q] == g.node_count() - 1 ? 1.0 : 0.0, 1e-14);
  }
}

TEST(ShapeFunctionLinear, OutsideTheGridIsAnError) {
  const auto g = test_grid();
  ShapeStencil st;
  Vec3 x = g.upper();
  x[2] = std::nextafter(x[2], 1e9);
  EXPECT_THROW(ShapeFunctionLinear().evaluate(g, x, st), pbms::Error);
  EXPECT_THROW(ShapeFunctionLinear().evaluate(g, {-2.0, 2.5, 1.0}, st), pbms::Error);
}

// ---------------------------------------------------------------- registry

TEST(ShapeFunctionRegistry, CreatesBuiltInStyles) {
  const auto sf = ShapeFunctionRegistry::create("linear");
  ASSERT_NE(sf, nullptr);
  EXPECT_EQ(sf->name(), "linear");
  EXPECT_EQ(sf->support_nodes(), 8);
  EXPECT_LE(sf->support_nodes(), ShapeStencil::kMaxNodes);
  const auto names = ShapeFunctionRegistry::names();
  EXPECT_NE(std::find(names.begin(), names.end(), "linear"), names.end());
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_TRUE(ShapeFunctionRegistry::contains("linear"));
  EXPECT_FALSE(ShapeFunctionRegistry::contains("Linear"));
}

TEST(ShapeFunctionRegistry, UnknownNameSaysWhatExists) {
  try {
    ShapeFunctionRegistry::create("gimp-typo");
    FAIL() << "no error for an unknown style";
  } catch (const pbms::Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("'gimp-typo'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("available: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("linear"), std::string::npos) << msg;
  }
}

TEST(ShapeFunctionRegistry, NewStylesNeedNoSolverChange) {
  // A stand-in for a later style; the registry only needs a factory.
  struct Renamed final : ShapeFunction {
    void evaluate(const RegularGrid& g, const Vec3& x, ShapeStencil& out) const override {
      ShapeFunctionLinear().evaluate(g, x, out);
    }
    int support_nodes() const override { return 8; }
    std::string_view name() const override { return "test-renamed-linear"; }
  };
  if (!ShapeFunctionRegistry::contains("test-renamed-linear")) {
    ShapeFunctionRegistry::add("test-renamed-linear", [] { return std::make_unique<Renamed>(); });
  }
  EXPECT_EQ(ShapeFunctionRegistry::create("test-renamed-linear")->name(), "test-renamed-linear");
  EXPECT_THROW(ShapeFunctionRegistry::add("linear", [] { return std::make_unique<Renamed>(); }),
               pbms::Error);
}

// ---------------------------------------------------------------- DDMP

namespace {

// Plain-gradient stencils in the CSR layout, to compare like with like.
GradientStencils plain_gradients(const std::vector<ShapeStencil>& st) {
  GradientStencils g;
  g.begin.push_back(0);
  for (const auto& s : st) {
    for (int q = 0; q < s.count; ++q) {
      g.node.push_back(s.node[q]);
      g.dN.push_back(s.dN[q]);
    }
    g.begin.push_back(g.node.size());
  }
  return g;
}

// Nodal force of a scalar (isotropic) stress sigma: f_i = -sum_p V_p sigma_p grad N_i.
std::vector<Vec3> nodal_force(const RegularGrid& g, const GradientStencils& gs,
                              const std::vector<double>& volume, const std::vector<double>& sigma) {
  std::vector<Vec3> f(static_cast<std::size_t>(g.node_count()), Vec3{});
  for (std::size_t p = 0; p < gs.particles(); ++p) {
    for (std::size_t k = gs.begin[p]; k < gs.begin[p + 1]; ++k) {
      for (int d = 0; d < 3; ++d) {
        f[static_cast<std::size_t>(gs.node[k])][d] -= volume[p] * sigma[p] * gs.dN[k][d];
      }
    }
  }
  return f;
}

// Sum over the transverse node layers of a grid one cell thick in y and z:
// the force on the 1-D node a.
double bar_force(const RegularGrid& g, const std::vector<Vec3>& f, int a) {
  double s = 0.0;
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < 2; ++b) s += f[static_cast<std::size_t>(g.node_index({a, b, c}))][0];
  return s;
}

// The same force in the nodal form: S_j = sum_p V_p sigma_p N_j(x_p), then
// f_i = -sum_j S_j D_ji (alpha = 0).
std::vector<Vec3> nodal_form_force(const RegularGrid& g, const DualDomainOperator& op,
                                   const std::vector<ShapeStencil>& st,
                                   const std::vector<double>& volume,
                                   const std::vector<double>& sigma) {
  std::vector<double> S(static_cast<std::size_t>(g.node_count()), 0.0);
  for (std::size_t p = 0; p < st.size(); ++p) {
    for (int q = 0; q < st[p].count; ++q) {
      S[static_cast<std::size_t>(st[p].node[q])] += volume[p] * sigma[p] * st[p].N[q];
    }
  }
  std::vector<Vec3> f(S.size(), Vec3{});
  for (std::int64_t j = 0; j < g.node_count(); ++j) {
    for (const auto& e : op.row(j)) {
      for (int d = 0; d < 3; ++d) {
        f[static_cast<std::size_t>(e.node)][d] -= S[static_cast<std::size_t>(j)] * e.d[d];
      }
    }
  }
  return f;
}

double tent(double x, double node, double h) {
  return std::max(0.0, 1.0 - std::abs(x - node) / h);
}

}  // namespace

TEST(Ddmp, StencilOwnNodesComeFirstAndAlphaOneIsPlainMpm) {
  const RegularGrid g({0, 0, 0}, 1.0, {6, 6, 6});
  const ShapeFunctionLinear sf;
  const auto pts = lattice_points(g, {1, 1, 1}, {5, 5, 5}, 2);
  const auto st = stencils_at(g, sf, pts);
  const DualDomainOperator op(g, sf, pts);
  EXPECT_EQ(op.occupied_cells().size(), 64u);
  const std::vector<double> one(pts.size(), 1.0);
  const auto gs = ddmp_gradients(op, st, one);
  for (std::size_t p = 0; p < pts.size(); ++p) {
    for (int q = 0; q < 8; ++q) {
      const std::size_t k = gs.begin[p] + static_cast<std::size_t>(q);
      ASSERT_EQ(gs.node[k], st[p].node[q]);
      for (int d = 0; d < 3; ++d) ASSERT_EQ(gs.dN[k][d], st[p].dN[q][d]);
    }
  }
  // The dual part reaches the neighbours of the 8 cell corners: 4^3 nodes.
  const auto dual = ddmp_gradients(op, st);
  const std::size_t inner = static_cast<std::size_t>(
      std::find(pts.begin(), pts.end(), Vec3{2.75, 2.25, 3.25}) - pts.begin());
  ASSERT_LT(inner, pts.size());
  EXPECT_EQ(dual.begin[inner + 1] - dual.begin[inner], 64u);
  EXPECT_THROW(ddmp_gradients(op, st, std::vector<double>(3, 0.0)), pbms::Error);
  EXPECT_THROW(ddmp_gradients(op, st, std::vector<double>(pts.size(), 1.5)), pbms::Error);
}

// The seed's 1-D program, Appendix 2: nodal stress averages enter the force
// as half the difference of the two neighbours, with half nodal volumes at
// the bar's ends; the strain rate is a nodal central difference.
TEST(Ddmp, OneDimensionReducesToNodalCentralDifferences) {
  const double h = 1.5;
  const int cells = 10, first = 2, last = 8;  // material in cells [2, 8)
  const RegularGrid g({0, 0, 0}, h, {cells, 1, 1});
  const ShapeFunctionLinear sf;
  const auto pts = lattice_points(g, {first, 0, 0}, {last, 1, 1}, 3);
  const auto st = stencils_at(g, sf, pts);
  const DualDomainOperator op(g, sf, pts);
  const auto gs = ddmp_gradients(op, st);  // alpha = 0: pure dual domain
  const double area = h * h;

  EXPECT_NEAR(op.nodal_volume(g.node_index({5, 0, 0})), h * area / 4, 1e-12);
  EXPECT_NEAR(op.nodal_volume(g.node_index({first, 1, 1})), h * area / 8, 1e-12);
  EXPECT_EQ(op.nodal_volume(g.node_index({first - 1, 0, 0})), 0.0);

  // Strain rate of an arbitrary nodal velocity profile v(x) along the bar.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> v1d(cells + 1);
  for (auto& v : v1d) v = u(rng);
  auto central = [&](int j) {
    if (j == first) return (v1d[j + 1] - v1d[j]) / h;
    if (j == last) return (v1d[j] - v1d[j - 1]) / h;
    return (v1d[j + 1] - v1d[j - 1]) / (2 * h);
  };
  for (std::size_t p = 0; p < pts.size(); ++p) {
    double dvdx = 0.0;
    for (std::size_t k = gs.begin[p]; k < gs.begin[p + 1]; ++k) {
      dvdx += v1d[static_cast<std::size_t>(g.node_ijk(gs.node[k])[0])] * gs.dN[k][0];
    }
    double expected = 0.0;
    for (int j = first; j <= last; ++j) expected += tent(pts[p][0], j * h, h) * central(j);
    ASSERT_NEAR(dvdx, expected, 1e-12);
  }

  // Nodal force of an arbitrary stress profile.
  std::vector<double> volume(pts.size(), std::pow(h / 3, 3)), sigma(pts.size());
  for (auto& s : sigma) s = 1e3 * u(rng);
  const auto f = nodal_force(g, gs, volume, sigma);
  std::vector<double> avg(cells + 1, 0.0);  // the seed's nodal average stress
  for (std::size_t p = 0; p < pts.size(); ++p) {
    for (int j = first; j <= last; ++j) avg[j] += volume[p] * sigma[p] * tent(pts[p][0], j * h, h);
  }
  for (int j = first; j <= last; ++j) avg[j] /= (j == first || j == last) ? h * area / 2 : h * area;
  for (int i = 0; i <= cells; ++i) {
    double expected = 0.0;
    if (i == first) expected = area * (avg[i + 1] + avg[i]) / 2;
    if (i == last) expected = -area * (avg[i] + avg[i - 1]) / 2;
    if (i > first && i < last) expected = area * (avg[i + 1] - avg[i - 1]) / 2;
    EXPECT_NEAR(bar_force(g, f, i), expected, 1e-9) << "node " << i;
  }
}

// A decomposed run builds one operator per rank from its own points. Kept
// as integrals, the parts add up to the whole grid's operator: summed rows
// over summed volumes give D_ji of one operator over all points.
TEST(Ddmp, IntegralRowsOfTwoPartsAddUpToTheWholeOperator) {
  const RegularGrid g({0.3, -0.7, 1.1}, 0.5, {8, 7, 6});
  const ShapeFunctionLinear sf;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> all, left, right;
  for (int p = 0; p < 300; ++p) {
    Vec3 x{};
    for (int d = 0; d < 3; ++d) x[d] = g.origin()[d] + g.cell_size() * (1.0 + 5.0 * u(rng));
    all.push_back(x);
    // Split on a cell face, as a grid partition does.
    (x[0] < g.origin()[0] + 3 * g.cell_size() ? left : right).push_back(x);
  }
  ASSERT_FALSE(left.empty());
  ASSERT_FALSE(right.empty());
  const DualDomainOperator whole(g, sf, all);
  const DualDomainOperator a(g, sf, left, {}, DualDomainRows::kIntegral);
  const DualDomainOperator b(g, sf, right, {}, DualDomainRows::kIntegral);
  int shared = 0;
  for (std::int64_t j = 0; j < g.node_count(); ++j) {
    const double v = a.nodal_volume(j) + b.nodal_volume(j);
    EXPECT_NEAR(v, whole.nodal_volume(j), 1e-15) << "node " << j;
    if (a.nodal_volume(j) > 0.0 && b.nodal_volume(j) > 0.0) ++shared;
    std::map<std::int64_t, Vec3> sum;
    for (const auto* op : {&a, &b}) {
      for (const auto& e : op->row(j)) {
        for (int d = 0; d < 3; ++d) sum[e.node][d] += e.d[d];
      }
    }
    const auto row = whole.row(j);
    ASSERT_EQ(row.size(), sum.size()) << "node " << j;
    for (const auto& e : row) {
      for (int d = 0; d < 3; ++d) ASSERT_NEAR(sum[e.node][d] / v, e.d[d], 1e-12);
    }
  }
  EXPECT_GT(shared, 10);  // the test reaches the nodes on the cut
}

TEST(Ddmp, LinearlyCompleteForAnyBlendAndArrangement) {
  const RegularGrid g({0.3, -0.7, 1.1}, 0.5, {8, 7, 6});
  const ShapeFunctionLinear sf;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);

  // Uniform block, and a ragged cloud whose region Omega has holes and steps.
  std::vector<std::vector<Vec3>> clouds{lattice_points(g, {1, 1, 1}, {7, 6, 5}, 2)};
  std::vector<Vec3> ragged;
  for (int p = 0; p < 400; ++p) {
    Vec3 x{};
    for (int d = 0; d < 3; ++d) x[d] = g.origin()[d] + g.cell_size() * (1.0 + 4.0 * u(rng));
    ragged.push_back(x);
  }
  clouds.push_back(ragged);

  // v(x) = a + B x: the velocity gradient must come out as B.
  const Vec3 a{0.3, -1.2, 2.0};
  const std::array<Vec3, 3> B{{{1.0, -2.0, 0.5}, {0.25, 3.0, -1.0}, {-0.75, 0.125, 2.0}}};

  for (const auto& pts : clouds) {
    const auto st = stencils_at(g, sf, pts);
    const DualDomainOperator op(g, sf, pts);
    std::vector<double> alpha(pts.size());
    for (auto& x : alpha) x = u(rng);
    for (const auto& blend : {std::vector<double>{}, alpha}) {
      const auto gs = ddmp_gradients(op, st, blend);
      double worst_grad = 0.0, worst_moment = 0.0, worst_L = 0.0;
      for (std::size_t p = 0; p < pts.size(); ++p) {
        const std::size_t b = gs.begin[p], n = gs.begin[p + 1] - b;
        const auto [e0, e1] = completeness_error(g, std::span(gs.node).subspan(b, n),
                                                 std::span(gs.dN).subspan(b, n), n);
        worst_grad = std::max(worst_grad, e0);
        worst_moment = std::max(worst_moment, e1);
        std::array<Vec3, 3> L{};
        for (std::size_t k = b; k < b + n; ++k) {
          const Vec3 X = g.node_position(gs.node[k]);
          for (int r = 0; r < 3; ++r) {
            const double v = a[r] + B[r][0] * X[0] + B[r][1] * X[1] + B[r][2] * X[2];
            for (int c = 0; c < 3; ++c) L[r][c] += v * gs.dN[k][c];
          }
        }
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) worst_L = std::max(worst_L, std::abs(L[r][c] - B[r][c]));
      }
      EXPECT_LT(worst_grad, 1e-12);
      EXPECT_LT(worst_moment, 1e-12);
      EXPECT_LT(worst_L, 1e-11);
    }
  }
}

TEST(Ddmp, PassesTheConstantStressPatchTest) {
  const RegularGrid g({0, 0, 0}, 1.0, {8, 8, 8});
  const ShapeFunctionLinear sf;
  const auto pts = lattice_points(g, {1, 1, 1}, {7, 7, 7}, 2);
  const auto st = stencils_at(g, sf, pts);
  const DualDomainOperator op(g, sf, pts);
  const auto f = nodal_force(g, ddmp_gradients(op, st), std::vector<double>(pts.size(), 0.125),
                             std::vector<double>(pts.size(), 7.0));
  double interior = 0.0, total_x = 0.0;
  for (std::int64_t n = 0; n < g.node_count(); ++n) {
    const auto ijk = g.node_ijk(n);
    total_x += f[static_cast<std::size_t>(n)][0];
    if (std::all_of(ijk.begin(), ijk.end(), [](int i) { return i > 1 && i < 7; })) {
      const auto& fn = f[static_cast<std::size_t>(n)];
      for (int d = 0; d < 3; ++d) interior = std::max(interior, std::abs(fn[d]));
    }
  }
  EXPECT_LT(interior, 1e-12);           // only the surface nodes feel a uniform stress
  EXPECT_LT(std::abs(total_x), 1e-11);  // momentum: the forces sum to zero
}

// One point crosses a cell face while the rest of the bar holds Omega fixed:
// the plain gradient of the face node's N jumps by 2/h (times the transverse
// weights), the DDMP gradient does not move.
TEST(Ddmp, GradientIsContinuousWhenAPointCrossesAFace) {
  const double h = 1.0;
  const RegularGrid g({0, 0, 0}, h, {12, 1, 1});
  const ShapeFunctionLinear sf;
  auto pts = lattice_points(g, {2, 0, 0}, {10, 1, 1}, 4);
  const DualDomainOperator op(g, sf, pts);
  const std::int64_t face_node = g.node_index({6, 0, 0});

  auto gradient_of_face_node = [&](double x, bool plain, bool blend) {
    const std::vector<Vec3> probe{{x, 0.5, 0.5}};
    const auto st = stencils_at(g, sf, probe);
    const std::vector<double> alpha{blend ? face_vanishing_blend(g, probe[0]) : 0.0};
    const auto gs = plain ? plain_gradients(st) : ddmp_gradients(op, st, alpha);
    for (std::size_t k = 0; k < gs.node.size(); ++k) {
      if (gs.node[k] == face_node) return gs.dN[k][0];
    }
    return 0.0;
  };
  const double eps = 1e-9;
  const double plain_jump = std::abs(gradient_of_face_node(6 - eps, true, false) -
                                     gradient_of_face_node(6 + eps, true, false));
  const double ddmp_jump = std::abs(gradient_of_face_node(6 - eps, false, false) -
                                    gradient_of_face_node(6 + eps, false, false));
  const double blended_jump = std::abs(gradient_of_face_node(6 - eps, false, true) -
                                       gradient_of_face_node(6 + eps, false, true));
  EXPECT_NEAR(plain_jump, 2.0 / h * 0.25, 1e-8);
  EXPECT_LT(ddmp_jump, 1e-8);
  EXPECT_LT(blended_jump, 1e-8);
  RecordProperty("plain_jump", std::to_string(plain_jump));
  RecordProperty("ddmp_jump", std::to_string(ddmp_jump));
  std::printf("[ face crossing ] |jump of dN/dx| plain %.3e, DDMP %.3e, DDMP+blend %.3e\n",
              plain_jump, ddmp_jump, blended_jump);
}

// Cell-crossing noise, quantified: a uniformly stressed body whose point
// spacing does not divide the cell slides by one cell. The exact force on an
// interior node is zero throughout. Plain MPM's force jumps each time a point
// crosses the node; the DDMP force changes only by the smooth quadrature
// error of the nodal averages.
TEST(Ddmp, CellCrossingNoiseIsSuppressed) {
  struct Setup {
    const char* name;
    RegularGrid grid;
    std::array<int, 3> node;  // watched interior node (for the bar: its x index)
    Vec3 direction;           // of the slide
  };
  const std::vector<Setup> setups{
      {"1-D bar", RegularGrid({0, 0, 0}, 1.0, {16, 1, 1}), {8, 0, 0}, {1, 0, 0}},
      {"3-D block", RegularGrid({0, 0, 0}, 1.0, {10, 10, 10}), {5, 5, 5}, {1, 0.37, 0.21}}};
  for (const auto& s : setups) {
    const auto& g = s.grid;
    const ShapeFunctionLinear sf;
    const bool bar = g.cells()[1] == 1;
    const double spacing = 1.0 / 3.3;  // 3.3 points per cell along each axis
    std::vector<Vec3> base;
    // Enough material that every cell the watched node's dual operator
    // reaches stays full during the slide: the exact force is then zero.
    const std::array<int, 3> count =
        bar ? std::array<int, 3>{26, 1, 1} : std::array<int, 3>{20, 20, 20};
    for (int k = 0; k < count[2]; ++k)
      for (int j = 0; j < count[1]; ++j)
        for (int i = 0; i < count[0]; ++i) {
          base.push_back(bar ? Vec3{4.0 + (i + 0.5) * spacing, 0.5, 0.5}
                             : Vec3{1.2 + (i + 0.5) * spacing, 1.2 + (j + 0.5) * spacing,
                                    1.2 + (k + 0.5) * spacing});
        }
    const double vp = bar ? spacing : spacing * spacing * spacing;
    // For the bar, the axial force on its cross-section at node x = 8 (its
    // four grid nodes also carry the lateral surface forces, which are real).
    auto watched = [&](const std::vector<Vec3>& f) {
      return bar ? Vec3{bar_force(g, f, s.node[0]), 0.0, 0.0}
                 : f[static_cast<std::size_t>(g.node_index(s.node))];
    };

    const int steps = bar ? 500 : 100;
    double plain_step = 0.0, ddmp_step = 0.0, plain_rms = 0.0, ddmp_rms = 0.0;
    Vec3 plain_prev{}, ddmp_prev{};
    const Vec3 centre = g.node_position(s.node);
    for (int n = 0; n <= steps; ++n) {
      const double shift = g.cell_size() * n / steps;
      // Only points within 2h of the watched node reach its force, plain or
      // DDMP (through the nodal averages of its neighbours); dropping the
      // rest keeps the test fast and changes nothing.
      std::vector<Vec3> pts;
      for (const auto& x0 : base) {
        Vec3 x{};
        bool near = true;
        for (int d = 0; d < 3; ++d) {
          x[d] = x0[d] + shift * s.direction[d];
          if (!bar || d == 0) near = near && std::abs(x[d] - centre[d]) < 2.0 * g.cell_size();
        }
        if (near) pts.push_back(x);
      }
      const std::vector<double> volume(pts.size(), vp), sigma(pts.size(), 1.0);
      const auto st = stencils_at(g, sf, pts);
      const DualDomainOperator op(g, sf, pts);
      const Vec3 fp = watched(nodal_force(g, plain_gradients(st), volume, sigma));
      const Vec3 fd = watched(nodal_force(g, ddmp_gradients(op, st), volume, sigma));
      if (n % 25 == 0) {
        // The nodal form of the header gives the same force.
        const Vec3 fn = watched(nodal_form_force(g, op, st, volume, sigma));
        for (int d = 0; d < 3; ++d) EXPECT_NEAR(fn[d], fd[d], 1e-12) << s.name;
      }
      for (int d = 0; d < 3; ++d) {
        plain_rms += fp[d] * fp[d];
        ddmp_rms += fd[d] * fd[d];
        if (n > 0) {
          plain_step = std::max(plain_step, std::abs(fp[d] - plain_prev[d]));
          ddmp_step = std::max(ddmp_step, std::abs(fd[d] - ddmp_prev[d]));
        }
      }
      plain_prev = fp;
      ddmp_prev = fd;
    }
    plain_rms = std::sqrt(plain_rms / (steps + 1));
    ddmp_rms = std::sqrt(ddmp_rms / (steps + 1));
    // Scale: the force one point's stress puts on a node, V_p sigma / h.
    const double unit = vp / g.cell_size();
    std::printf(
        "[ cell crossing ] %s, interior node force / (V_p sigma / h): largest step-to-step "
        "change plain %.3f, DDMP %.2e; rms plain %.3f, DDMP %.2e\n",
        s.name, plain_step / unit, ddmp_step / unit, plain_rms / unit, ddmp_rms / unit);
    EXPECT_GT(plain_step / unit, 0.2) << s.name;  // a point crossing: order one
    EXPECT_LT(ddmp_step, 1e-2 * plain_step) << s.name;
    EXPECT_LT(ddmp_rms, 0.1 * plain_rms) << s.name;
  }
}

TEST(Ddmp, FaceVanishingBlend) {
  const RegularGrid g({0, 0, 0}, 2.0, {3, 3, 3});
  EXPECT_DOUBLE_EQ(face_vanishing_blend(g, {1.0, 3.0, 5.0}), 1.0);  // cell centre
  EXPECT_DOUBLE_EQ(face_vanishing_blend(g, {1.0, 3.0, 5.0}, 0.5), 0.5);
  EXPECT_DOUBLE_EQ(face_vanishing_blend(g, {2.0, 3.0, 5.0}), 0.0);  // on a face
  EXPECT_DOUBLE_EQ(face_vanishing_blend(g, {6.0, 6.0, 6.0}), 0.0);  // far corner
  // 1-D profile along x through cell centres in y and z: 4 xi (1 - xi).
  EXPECT_NEAR(face_vanishing_blend(g, {0.5, 3.0, 5.0}), 4 * 0.25 * 0.75, 1e-15);
  EXPECT_THROW(face_vanishing_blend(g, {7.0, 1.0, 1.0}), pbms::Error);
}
