// The neck between two sintering bodies (neck_probe), on particle sets whose
// neck is known: two fcc balls apart, and the same joined by a bar.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fcc_particles.hpp"
#include "pbms/analysis/neck_width.hpp"
#include "stage/neck_probe.hpp"

using namespace pbms;

namespace {

constexpr double kA = 7.23;  // lattice constant

// fcc sites (lattice constant kA, origin 0) for which `inside` holds, in a
// 40 a cube around the origin; groups: 1 for x < 0, 2 for x >= 0.
struct Body : test::FccParticles {
  template <class Inside>
  explicit Body(Inside inside)
      : FccParticles(kA, {{{-20, 19}, {-20, 19}, {-20, 19}}}, inside,
                     [](const coupling::Vec3& p) { return p[0] < 0.0 ? 1U : 2U; }) {}
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

// md_driver measures its atoms by the one-pass form of the same rule: on the
// same members it gives the probe's neck exactly, and an atomic crystal
// (lattice constant a/2, every length halved) has half the neck.
TEST(NeckProbe, AtomsAreMeasuredByTheSameRule) {
  const coupling::Vec3 l{-5 * kA + 0.5 * kA, 0.5 * kA, 0.5 * kA},
      r{5 * kA + 0.5 * kA, 0.5 * kA, 0.5 * kA};
  const Body body([&](const coupling::Vec3& p) {
    const bool bar = p[0] > l[0] && p[0] < r[0] && std::hypot(p[1] - l[1], p[2] - l[2]) <= 1.7 * kA;
    return distance(p, l) <= 4 * kA || distance(p, r) <= 4 * kA || bar;
  });
  std::vector<int> which;
  std::vector<std::array<double, 3>> half;
  for (std::size_t i = 0; i < body.x.size(); ++i) {
    which.push_back(body.groups[i] == 1U ? 0 : 1);
    half.push_back({0.5 * body.x[i][0], 0.5 * body.x[i][1], 0.5 * body.x[i][2]});
  }
  const double probe = neck_of(body);
  ASSERT_GT(probe, 0.0);
  const auto particles = analysis::neck_between(body.x, which, kA);
  EXPECT_EQ(particles.width, probe);
  const auto atoms = analysis::neck_between(half, which, 0.5 * kA);
  EXPECT_NEAR(atoms.width, 0.5 * probe, 1e-12 * probe);
  EXPECT_NEAR(atoms.centre_distance, 0.5 * particles.centre_distance, 1e-12 * probe);
  // Joined: nearest neighbours across the join.
  EXPECT_NEAR(particles.closest, kA / std::sqrt(2.0), 1e-9);
}

// Balls of radius 4 a with centres 9 a apart on a lattice line: their
// poles are a lattice constant apart, the closest approach; they do not
// touch (1.1 a/√2), and beyond two lattice constants the approach is capped.
TEST(NeckProbe, ClosestApproachOfBallsApart) {
  const coupling::Vec3 l{-4.0 * kA, 0.0, 0.0}, r{5.0 * kA, 0.0, 0.0}, far{7.0 * kA, 0.0, 0.0};
  const auto ball = [](const coupling::Vec3& c) {
    return Body([&](const coupling::Vec3& p) { return distance(p, c) <= 4 * kA + 1e-9; }).x;
  };
  EXPECT_NEAR(analysis::closest_approach(ball(l), ball(r), analysis::closest_reach(kA)), kA, 1e-9);
  EXPECT_GT(kA, analysis::touch_distance(kA));
  EXPECT_EQ(analysis::closest_approach(ball(l), ball(far), analysis::closest_reach(kA)),
            analysis::closest_reach(kA));
}
