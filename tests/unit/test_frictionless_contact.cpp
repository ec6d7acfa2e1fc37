// Frictionless contact between two velocity fields on one grid
// (grid/frictionless_contact.hpp): the impulse at one node against the
// collision of two masses worked by hand, and two solvers whose fields meet
// through it (the in-process form of the gas's contact with a body).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pbms/grid/frictionless_contact.hpp"
#include "pbms/grid/mpm_solver.hpp"
#include "pbms/grid/shape_function.hpp"
#include "pbms/grid/stressless_particle.hpp"

using namespace pbms::grid;

TEST(FrictionlessContact, NormalPointsFromTheFirstFieldIntoTheSecond) {
  // a's mass rises towards -x, b's towards +x: from a into b is +x.
  const ContactVec n = contact_normal({-2.0, 0.0, 0.0}, {3.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(n[0], 1.0);
  EXPECT_EQ(n[1], 0.0);
  const ContactVec none = contact_normal({1.0, 2.0, 3.0}, {1.0, 2.0, 3.0});
  EXPECT_EQ(none[0] * none[0] + none[1] * none[1] + none[2] * none[2], 0.0);
}

// Masses 2 and 3 meeting head-on along x at +1 and -1 end with the common
// velocity (2 - 3) / 5 = -0.2 along x; each keeps its velocity across.
TEST(FrictionlessContact, ApproachingFieldsTakeOneNormalVelocityAndKeepTheirTangentialOnes) {
  const double ma = 2.0, mb = 3.0;
  const ContactVec pa{ma * 1.0, ma * 0.5, 0.0}, pb{mb * -1.0, 0.0, mb * 0.2};
  const ContactVec n{1.0, 0.0, 0.0};
  const ContactVec ja = frictionless_contact_impulse(ma, pa, mb, pb, n);
  const ContactVec jb = frictionless_contact_impulse(mb, pb, ma, pa, {-1.0, 0.0, 0.0});
  EXPECT_NEAR((pa[0] + ja[0]) / ma, -0.2, 1e-15);
  EXPECT_NEAR((pb[0] + jb[0]) / mb, -0.2, 1e-15);
  EXPECT_EQ(ja[1], 0.0);
  EXPECT_EQ(jb[2], 0.0);
  // Moving apart, or side by side, they are left alone.
  const ContactVec apart = frictionless_contact_impulse(ma, {-2.0, 1.0, 0.0}, mb, pb, {-1, 0, 0});
  EXPECT_EQ(apart[0], 0.0);
  const ContactVec sliding = frictionless_contact_impulse(ma, {0.0, 5.0, 0.0}, mb, {0, 0, 0}, n);
  EXPECT_EQ(sliding[1], 0.0);
}

// The two programs compute each side's impulse apart: they must cancel
// bit for bit, whatever the numbers, for momentum to hold to round-off.
TEST(FrictionlessContact, TheSwappedCallGivesTheExactNegative) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const double ma = 1.0 + u(rng) * u(rng), mb = 0.01 + std::abs(u(rng));
    const ContactVec pa{u(rng), u(rng), u(rng)}, pb{u(rng), u(rng), u(rng)};
    const ContactVec ga{u(rng), u(rng), u(rng)}, gb{u(rng), u(rng), u(rng)};
    const ContactVec ja = frictionless_contact_impulse(ma, pa, mb, pb, contact_normal(ga, gb));
    const ContactVec jb = frictionless_contact_impulse(mb, pb, ma, pa, contact_normal(gb, ga));
    for (std::size_t c = 0; c < 3; ++c) ASSERT_EQ(ja[c], -jb[c]) << "trial " << trial;
    if (ja[0] != 0.0) ++hits;
  }
  EXPECT_GT(hits, 100);  // approaching pairs were among them
}

namespace {

// Stressless points, two per cell edge, filling cells [x0, x1) x [0, 4)^2.
MaterialPoints block(double x0, double x1, const Vec3& v) {
  MaterialPoints pts;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = static_cast<int>(2 * x0); i < static_cast<int>(2 * x1); ++i) {
        MaterialPointState s;
        s.density = 1.0;
        pts.add(static_cast<std::int64_t>(pts.size()),
                {(i + 0.5) / 2, (j + 0.5) / 2, (k + 0.5) / 2}, 0.125, s, 0);
        pts.v.back() = v;
      }
  return pts;
}

std::unique_ptr<MpmSolver> field(const RegularGrid& g, ContactField role, PointMove move) {
  std::vector<std::unique_ptr<Material>> m;
  m.push_back(std::make_unique<StresslessParticle>());
  SolverOptions opt;
  opt.contact = role;
  opt.move = move;
  opt.small_mass_fraction = 0.0;
  return std::make_unique<MpmSolver>(g, ShapeFunctionRegistry::create("linear"), std::move(m), opt);
}

// What the link does: `from`'s lanes [first, first + count) (and its mass
// gradient) into `to`'s records of the other field, on the same nodes.
void copy_to_other(MpmSolver& from, MpmSolver& to, int first, int count) {
  const auto src = from.nodal_sums();
  const auto f = from.contact_fields();
  const auto t = to.contact_fields();
  for (std::int64_t i = 0; i < src.nodes.count(); ++i) {
    for (int c = first; c < first + count; ++c) {
      t.other_sums.data[i * t.other_sums.stride + c] = src.data[i * src.stride + c];
    }
    for (int c = 0; c < 3; ++c) t.other_gradient.data[i * 3 + c] = f.gradient.data[i * 3 + c];
  }
}

struct Meeting {
  Vec3 gas_velocity_at_plane{};  // at an inner node of the plane x = 3
  Vec3 body_velocity_at_plane{};
  Vec3 gas_move_velocity_at_plane{};  // what the points moved with there
  Vec3 body_move_velocity_at_plane{};
  Vec3 momentum_before{}, momentum_after{};
};

Vec3 momentum(const MaterialPoints& a, const MaterialPoints& b) {
  Vec3 p{0.0, 0.0, 0.0};
  for (const MaterialPoints* s : {&a, &b})
    for (std::size_t i = 0; i < s->size(); ++i)
      for (std::size_t c = 0; c < 3; ++c) p[c] += s->mass[i] * s->v[i][c];
  return p;
}

// The move's phases, with the link's exchange of the midpoint sums.
void move_both(MpmSolver& gas, MaterialPoints& pg, MpmSolver& body, MaterialPoints& pb,
               const BoundaryConditions& bc, double dt) {
  gas.update_stress_and_map_midpoints(pg, bc, dt);
  body.update_stress_and_map_midpoints(pb, bc, dt);
  gas.complete_midpoint_sums();
  body.complete_midpoint_sums();
  copy_to_other(gas, body, sums::kMass, 4);
  copy_to_other(body, gas, sums::kMass, 4);
  gas.move_from_midpoints(pg, bc, dt);
  body.move_from_midpoints(pb, bc, dt);
}

// A gas block in cells x in [1, 3) moving at `v` next to a body block at
// rest in [3, 5): they share the node plane x = 3. One step.
Meeting meet(const Vec3& v, PointMove move = PointMove::kStepStart) {
  const RegularGrid g({0, 0, 0}, 1.0, {6, 4, 4});
  auto gas = field(g, ContactField::kSurfaceFromOwnMass, move);
  auto body = field(g, ContactField::kSurfaceFromOtherMass, move);
  MaterialPoints pg = block(1, 3, v), pb = block(3, 5, {0.0, 0.0, 0.0});
  const BoundaryConditions bc;
  const double dt = 0.1;
  Meeting out;
  out.momentum_before = momentum(pg, pb);
  gas->begin_step(pg);
  body->begin_step(pb);
  gas->map_to_grid(pg, bc, dt);
  body->map_to_grid(pb, bc, dt);
  gas->complete_nodal_sums();
  body->complete_nodal_sums();
  copy_to_other(*gas, *body, sums::kMass, 7);
  copy_to_other(*body, *gas, sums::kMass, 7);
  gas->update_nodes(bc, dt);
  body->update_nodes(bc, dt);
  const auto node = static_cast<std::size_t>(g.node_box().local_index({3, 2, 2}));
  out.gas_velocity_at_plane = gas->nodal_velocity(node);
  out.body_velocity_at_plane = body->nodal_velocity(node);
  gas->map_to_points(pg, bc, dt);
  body->map_to_points(pb, bc, dt);
  gas->complete_remap_sums();
  body->complete_remap_sums();
  copy_to_other(*gas, *body, sums::kMomentum, 3);
  copy_to_other(*body, *gas, sums::kMomentum, 3);
  move_both(*gas, pg, *body, pb, bc, dt);
  out.gas_move_velocity_at_plane = gas->move_velocity(node);
  out.body_move_velocity_at_plane = body->move_velocity(node);
  out.momentum_after = momentum(pg, pb);
  return out;
}

}  // namespace

// Driven into the body, the gas at the shared plane takes the body's
// velocity along the normal (the two nodal masses' common one) and keeps
// its own across; both blocks' momentum together is kept to round-off.
TEST(FrictionlessContact, AGasDrivenIntoABodySlidesAlongItWithoutEnteringIt) {
  const Meeting m = meet({1.0, 0.5, 0.0});
  const Vec3& vg = m.gas_velocity_at_plane;
  const Vec3& vb = m.body_velocity_at_plane;
  EXPECT_GT(vb[0], 0.1);  // the body was pushed
  EXPECT_NEAR(vg[0], vb[0], 1e-12);
  EXPECT_NEAR(vg[1], 0.5, 1e-12);  // the gas slides on
  EXPECT_NEAR(vb[1], 0.0, 1e-12);  // without dragging the body
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_NEAR(m.momentum_after[c], m.momentum_before[c], 1e-12 * 256.0) << "axis " << c;
  }
}

// Moving away from the body the gas is not held back.
TEST(FrictionlessContact, AGasMovingAwayFromABodyIsLeftAlone) {
  const Meeting m = meet({-1.0, 0.5, 0.0});
  EXPECT_DOUBLE_EQ(m.gas_velocity_at_plane[0], -1.0);
  EXPECT_EQ(m.body_velocity_at_plane[0], 0.0);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(m.momentum_after[c], m.momentum_before[c]) << "axis " << c;
  }
}

// With the midpoint move the fields meet again where the points' midpoints
// map: at the shared plane both move with one velocity along the normal,
// the gas keeps sliding across, and the momentum is kept to round-off.
TEST(FrictionlessContact, AtTheMidpointsTheGasStillMeetsTheBody) {
  const Meeting m = meet({1.0, 0.5, 0.0}, PointMove::kMidpoint);
  const Vec3& vg = m.gas_move_velocity_at_plane;
  const Vec3& vb = m.body_move_velocity_at_plane;
  EXPECT_GT(vb[0], 0.1);
  EXPECT_LT(vg[0], 0.9);  // held back from its own 1
  EXPECT_NEAR(vg[0], vb[0], 1e-12);
  EXPECT_GT(vg[1], 0.4);  // still sliding
  EXPECT_NEAR(vb[1], 0.0, 1e-12);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_NEAR(m.momentum_after[c], m.momentum_before[c], 1e-12 * 256.0) << "axis " << c;
  }
}
