#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "pbms/analysis/gauge_section.hpp"
#include "pbms/analysis/tension_test.hpp"

using namespace pbms;
using namespace pbms::analysis;

namespace {

struct PairForce {
  std::size_t i, j;
  double f;  // on i along the axis; j takes −f
};

}  // namespace

// Σ w_i f_i is the force across a plane, averaged over every plane of the
// gauge. The reference counts, plane by plane, the pairs that straddle it,
// which never looks at the weights: any antisymmetric pair forces will do.
TEST(GaugeSection, WeightedForceIsThePlaneAveragedForceAcrossTheGauge) {
  GaugeSection g;
  g.lo = 10.0;
  g.hi = 30.0;
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> where(0.0, 40.0), force(-1.0, 1.0);
  std::vector<double> x(400);
  for (double& xi : x) xi = where(gen);
  std::vector<PairForce> pairs;
  std::vector<double> f(x.size(), 0.0);
  std::uniform_int_distribution<std::size_t> pick(0, x.size() - 1);
  for (int k = 0; k < 3000; ++k) {
    const std::size_t i = pick(gen), j = pick(gen);
    if (i == j || std::abs(x[i] - x[j]) > 6.0) continue;
    pairs.push_back({i, j, force(gen)});
    f[i] += pairs.back().f;
    f[j] -= pairs.back().f;
  }
  double weighted = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) weighted += g.weight(x[i]) * f[i];

  const int planes = 20000;
  double mean = 0.0;
  for (int k = 0; k < planes; ++k) {
    const double plane = g.lo + (g.hi - g.lo) * (k + 0.5) / planes;
    for (const PairForce& p : pairs) {
      const bool i_behind = x[p.i] < plane, j_behind = x[p.j] < plane;
      if (i_behind && !j_behind) mean += p.f;
      if (j_behind && !i_behind) mean -= p.f;
    }
  }
  mean /= planes;
  // The midpoint rule over 2e4 planes places each of the ~2,500 pairs' ends
  // to 1e-3 Å of 20 Å: errors of 5e-5 |f| each, random in sign, ~3e-3 in all.
  EXPECT_NEAR(weighted, mean, 1e-2);
  EXPECT_GT(std::abs(mean), 0.1);  // not trivially zero
}

// A uniform stretch of a lattice gives its strain exactly, whatever rigid
// shift comes with it, and the section is the members' extents plus one
// spacing.
TEST(GaugeSection, UniformStretchReadsItsStrainAndSection) {
  GaugeSection g;
  g.lo = 20.0;
  g.hi = 80.0;
  const double strain = 0.037, shift = -4.2;
  GaugeSums s;
  for (int ix = 0; ix <= 100; ++ix) {
    for (int iy = 0; iy < 5; ++iy) {
      for (int iz = 0; iz < 4; ++iz) {
        const double x0 = ix;
        const int h = g.half(x0);
        if (h >= 0) s.add_member(h, x0 * (1.0 + strain) + shift, {2.0 * iy, 2.0 * iz});
      }
    }
  }
  GaugeSums start;
  for (int ix = 20; ix <= 80; ++ix) start.add_member(g.half(ix), ix, {0.0, 0.0});
  EXPECT_NEAR(s.centroid_distance() / start.centroid_distance() - 1.0, strain, 1e-13);
  EXPECT_DOUBLE_EQ(s.cross_section(2.0), 10.0 * 8.0);
}

namespace {

// A J2 rod's gauge: linear to 10 GPa at E = 80 GPa, then flat, with noise.
void plateau(std::vector<double>& strain, std::vector<double>& stress) {
  std::mt19937_64 gen(3);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (int k = 0; k <= 400; ++k) {
    const double e = 0.0005 * k;
    strain.push_back(e);
    stress.push_back(std::min(80.0 * e, 10.0) + noise(gen));
  }
}

double scalar(const StageResults& r, const std::string& key) {
  const auto v = r.scalar(key);
  EXPECT_TRUE(v.has_value()) << key;
  return v.value_or(std::nan(""));
}

TensionTest with_gauge() {
  TensionTest t;
  t.gauge = GaugeSection{};
  return t;
}

}  // namespace

TEST(GaugeSection, PlateauGivesTheModulusAndTheYieldStress) {
  std::vector<double> strain, stress;
  plateau(strain, stress);
  StageResults r;
  with_gauge().report_gauge(r, strain, stress, "tension");
  // The fit stops at half the plateau, inside the linear part.
  EXPECT_NEAR(scalar(r, "gauge_youngs_modulus"), 80.0, 1.0);
  // The smoothed maximum of noise 0.05 GPa about 10 GPa.
  EXPECT_NEAR(scalar(r, "gauge_yield_stress"), 10.0, 0.1);
  EXPECT_EQ(r.attributes.count("gauge_yield_note"), 1U);
}

TEST(GaugeSection, StillRisingCurveHasNoYield) {
  std::vector<double> strain, stress;
  for (int k = 0; k <= 200; ++k) {
    strain.push_back(0.0005 * k);
    stress.push_back(80.0 * strain.back());
  }
  StageResults r;
  with_gauge().report_gauge(r, strain, stress, "tension");
  EXPECT_NEAR(scalar(r, "gauge_youngs_modulus"), 80.0, 1e-9);
  EXPECT_FALSE(r.scalar("gauge_yield_stress").has_value());
}
