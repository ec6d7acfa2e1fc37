// The rod probe (rod_probe) on an fcc rod whose bend is known: straight,
// with its particles moved along the axis only, and bent into an arc.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fcc_particles.hpp"
#include "stage/rod_probe.hpp"

using namespace pbms;

namespace {

constexpr double kA = 7.23;  // lattice constant

// The fcc sites within 2 a of the z axis over 18 a: each (002) plane is
// symmetric about the axis, so every slab's centroid is on it. Ids spaced
// by 3 from 1000, as a rod cut from a larger body has them.
struct Rod : test::FccParticles {
  Rod()
      : FccParticles(
            kA, {{{-3, 3}, {-3, 3}, {0, 17}}},
            [](const coupling::Vec3& p) { return std::hypot(p[0], p[1]) <= 2 * kA; },
            [](const coupling::Vec3&) { return 1U; }, 1000, 3) {}
};

double bend_of(dpd::RodProbe& probe, const Rod& rod) {
  probe.sample(1.0, rod.view());
  StageResults r;
  probe.report(r);
  return r.scalar("rod_deflection_r").value_or(-1.0);
}

}  // namespace

// Particles moving along the axis, as thermal motion and a neck drawing at
// the rod's end move them, cross the slabs' bounds; a slab binned by where
// its particles are now gains and loses some of each plane, and its
// centroid leaves the axis (about 2 Å here). Kept in the slabs they
// started in, the centre line stays on the axis.
TEST(RodProbe, MotionAlongTheAxisDoesNotBendTheRod) {
  Rod rod;
  dpd::RodProbe probe(MPI_COMM_SELF, {"r", "rod", 2}, 1U, kA, rod.view());
  EXPECT_NEAR(bend_of(probe, rod), 0.0, 1e-9);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> along(-0.6 * kA, 0.6 * kA);
  for (auto& p : rod.x) p[2] += along(gen);
  EXPECT_NEAR(bend_of(probe, rod), 0.0, 1e-9);
}

// Bent into an arc of sagitta s over the rod: the probe reads s, to the
// slabs' averaging of the arc over their two planes.
TEST(RodProbe, AnArcReadsItsSagitta) {
  Rod rod;
  dpd::RodProbe probe(MPI_COMM_SELF, {"r", "rod", 2}, 1U, kA, rod.view());
  const double half = 8.5 * kA, s = 3.0;  // the slabs' centroids run 0.25 a .. 17.25 a
  const double radius = (half * half + s * s) / (2 * s);
  for (auto& p : rod.x) {
    const double z = p[2] - 0.25 * kA - half;
    p[0] += std::sqrt(radius * radius - z * z) - (radius - s);
  }
  EXPECT_NEAR(bend_of(probe, rod), s, 0.02 * s);
}

// The slabs' bounds fall midway between planes wherever the rod's lowest
// particle stands: one particle 2.4 Å out of the end face (on the axis, so
// that it moves no centroid) and the others up to 0.8 Å off their planes
// along the axis. Bounds set from the lowest particle fall 0.6 Å from a
// plane and split it between two slabs, whose centroids then leave the
// axis.
TEST(RodProbe, AParticleOutOfTheEndFaceDoesNotSetTheSlabs) {
  Rod rod;
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> along(-0.8, 0.8);
  for (auto& p : rod.x) p[2] += along(gen);
  rod.id.push_back(1);
  rod.x.push_back({0.0, 0.0, -2.4});
  rod.v.push_back({0, 0, 0});
  rod.mass.push_back(1.0);
  rod.groups.push_back(1U);
  dpd::RodProbe probe(MPI_COMM_SELF, {"r", "rod", 2}, 1U, kA, rod.view());
  EXPECT_NEAR(bend_of(probe, rod), 0.0, 1e-9);
}
