// The neck between two sintering bodies (neck_probe), on particle sets whose
// neck is known: two fcc balls apart, and the same joined by a bar.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "stage/neck_probe.hpp"

using namespace pbms;

namespace {

constexpr double kA = 7.23;  // lattice constant

// fcc sites (lattice constant kA, origin 0) for which `inside` holds, in a
// 40 a cube around the origin; groups: 1 for x < 0, 2 for x >= 0.
struct Body {
  std::vector<std::int64_t> id;
  std::vector<coupling::Vec3> x, v;
  std::vector<double> mass;
  std::vector<std::uint32_t> groups;

  template <class Inside>
  explicit Body(Inside inside) {
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    for (int i = -20; i < 20; ++i) {
      for (int j = -20; j < 20; ++j) {
        for (int k = -20; k < 20; ++k) {
          for (const auto& b : basis) {
            const coupling::Vec3 p{(i + b[0]) * kA, (j + b[1]) * kA, (k + b[2]) * kA};
            if (!inside(p)) continue;
            id.push_back(static_cast<std::int64_t>(id.size()));
            x.push_back(p);
            v.push_back({0, 0, 0});
            mass.push_back(1.0);
            groups.push_back(p[0] < 0.0 ? 1U : 2U);
          }
        }
      }
    }
  }
  [[nodiscard]] coupling::ParticleView view() const { return {x.size(), id, x, v, mass, groups}; }
};

double distance(const coupling::Vec3& p, const coupling::Vec3& c) {
  return std::hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]);
}

double neck_of(const Body& body) {
  dpd::NeckProbe probe(MPI_COMM_SELF, {"pair", "left", "right"}, 1U, 2U, kA);
  probe.sample(0.0, body.view());
  StageResults r;
  probe.report(r, 1.0);
  return r.scalar("neck_final_pair").value_or(-1.0);
}

}  // namespace

// Balls of radius 4 a whose centres are 10 a apart: 2 a between them, no neck.
TEST(NeckProbe, SeparateBodiesHaveNoNeck) {
  const coupling::Vec3 l{-5 * kA + 0.5 * kA, 0.5 * kA, 0.5 * kA},
      r{5 * kA + 0.5 * kA, 0.5 * kA, 0.5 * kA};
  const Body body([&](const coupling::Vec3& p) {
    return distance(p, l) <= 4 * kA || distance(p, r) <= 4 * kA;
  });
  EXPECT_EQ(neck_of(body), 0.0);
}

// The same balls joined by a bar of radius R along the line between them:
// the neck is the bar, 2 R, to the lattice's discreteness (a slab holds
// about 60 sites; 10 % is 3 sigma of its count's noise over positions).
TEST(NeckProbe, ABarBetweenTheBallsIsTheNeck) {
  const coupling::Vec3 l{-5 * kA + 0.5 * kA, 0.5 * kA, 0.5 * kA},
      r{5 * kA + 0.5 * kA, 0.5 * kA, 0.5 * kA};
  const double R = 2.2 * kA;
  const Body body([&](const coupling::Vec3& p) {
    const bool bar = p[0] > l[0] && p[0] < r[0] && std::hypot(p[1] - l[1], p[2] - l[2]) <= R;
    return distance(p, l) <= 4 * kA || distance(p, r) <= 4 * kA || bar;
  });
  EXPECT_NEAR(neck_of(body) / (2 * R), 1.0, 0.1);
}
