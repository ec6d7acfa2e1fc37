#include <gtest/gtest.h>

// GCC 12 warns inside its own AVX-512 intrinsics when Eigen uses them
// (GCC bug 105593, fixed in 13); nothing of ours is uninitialised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "materials/cubic_j2_plasticity.hpp"
#include "materials/ideal_gas.hpp"
#include "materials/j2_plasticity.hpp"
#include "materials/linear_elastic.hpp"
#include "materials/material_registry.hpp"
#include "pbms/error.hpp"

using namespace pbms::mpm;
using namespace pbms::grid;

namespace {

Mat3 diagonal_rate(double xx, double yy, double zz) {
  Mat3 l = Mat3::Zero();
  l(0, 0) = xx;
  l(1, 1) = yy;
  l(2, 2) = zz;
  return l;
}

// Velocity gradient of a rigid spin omega about a unit axis: v = omega n x x.
Mat3 spin_rate(const Eigen::Vector3d& axis, double omega) {
  const Eigen::Vector3d n = omega * axis.normalized();
  Mat3 l;
  l << 0, -n.z(), n.y(), n.z(), 0, -n.x(), -n.y(), n.x(), 0;
  return l;
}

double relative_error(double value, double expected) {
  return std::abs(value - expected) / std::abs(expected);
}

// Invariants of a symmetric tensor: trace, J2 of the deviator, determinant.
Eigen::Vector3d invariants(const SymmetricTensor& t) {
  const SymmetricTensor s = deviator(t);
  return {t.trace(), 0.5 * double_contraction(s, s), t.to_matrix().determinant()};
}

// Drives one point in uniaxial stress: each step the xx strain increment is
// imposed and the equal lateral increments are solved (secant on sigma_yy,
// which is piecewise linear in them) so that the lateral stress stays zero.
MaterialPointState uniaxial_stress_step(const Material& m, const MaterialPointState& state,
                                        double dexx, double poisson_ratio) {
  auto trial = [&](double lateral) {
    MaterialPointState next = state;
    m.update(diagonal_rate(dexx, lateral, lateral), 1.0, next);
    return next;
  };
  double a = -poisson_ratio * dexx;
  double b = -0.5 * dexx;
  double fa = trial(a).stress[1];
  double fb = trial(b).stress[1];
  for (int it = 0; it < 50 && fb != 0.0 && fa != fb; ++it) {
    const double c = b - fb * (b - a) / (fb - fa);
    a = b;
    fa = fb;
    b = c;
    fb = trial(b).stress[1];
  }
  return trial(b);
}

}  // namespace

// --- Block update -----------------------------------------------------------

// The solver updates points a block at a time through update_block; every
// material must give what update() gives point by point. Random states and
// velocity gradients (spin included), one run in the middle of a block, so
// that points outside [begin, end) must come out untouched.
TEST(MaterialBlock, UpdateBlockMatchesUpdatePointByPoint) {
  std::vector<std::unique_ptr<Material>> materials;
  materials.push_back(std::make_unique<LinearElastic>(100.0, 0.3));
  materials.push_back(std::make_unique<J2Plasticity>(100.0, 0.3, 0.05, 2.0));
  materials.push_back(std::make_unique<IdealGas>(1.4));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double dt = 0.01;
  for (const auto& m : materials) {
    MaterialBlock block{};
    std::vector<MaterialPointState> expected(MaterialBlock::kSize);
    for (std::size_t i = 0; i < MaterialBlock::kSize; ++i) {
      MaterialPointState s = m->initial_state(1.0 + 0.1 * u(rng), 0.1 + 0.05 * u(rng));
      if (m->style() != IdealGas::kStyle) {
        for (int c = 0; c < 6; ++c) s.stress[c] += 0.05 * u(rng);
      }
      Mat3 l;
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) l(a, b) = u(rng);
      }
      block.set_state(i, s);
      block.set_velocity_gradient(i, l);
      expected[i] = s;
      if (i >= 5 && i < 61) m->update(l, dt, expected[i]);
    }
    m->update_block(block, 5, 61, dt);
    for (std::size_t i = 0; i < MaterialBlock::kSize; ++i) {
      const MaterialPointState got = block.state(i);
      for (int c = 0; c < 6; ++c) {
        EXPECT_NEAR(got.stress[c], expected[i].stress[c],
                    1e-14 * (1.0 + std::abs(expected[i].stress[c])))
            << m->style() << " point " << i << " component " << c;
      }
      EXPECT_NEAR(got.plastic_strain, expected[i].plastic_strain, 1e-14) << m->style();
      EXPECT_NEAR(got.internal_energy, expected[i].internal_energy,
                  1e-14 * (1.0 + std::abs(expected[i].internal_energy)))
          << m->style();
    }
  }
}

// --- Linear elastic --------------------------------------------------------

TEST(LinearElastic, UniaxialStrainPatchLoadAndUnload) {
  const LinearElastic m(1.2e6, 0.3);
  const double lambda = m.elasticity().lambda;
  const double mu = m.elasticity().shear_modulus;
  MaterialPointState state = m.initial_state(8.9, 0.0);
  double strain = 0.0;
  const double dt = 0.01;
  for (int step = 0; step < 160; ++step) {
    const double rate = step < 100 ? 1e-3 : -1e-3;  // load to 1e-3, unload to 4e-4
    m.update(diagonal_rate(rate, 0, 0), dt, state);
    strain += rate * dt;
    EXPECT_LT(relative_error(state.stress[0], (lambda + 2 * mu) * strain), 1e-10);
    EXPECT_LT(relative_error(state.stress[1], lambda * strain), 1e-10);
    EXPECT_LT(relative_error(state.stress[2], lambda * strain), 1e-10);
    for (int k = 3; k < 6; ++k) EXPECT_EQ(state.stress[k], 0.0);
  }
  EXPECT_NEAR(strain, 4e-4, 1e-15);
  EXPECT_LT(relative_error(m.stored_energy_density(state), 0.5 * state.stress[0] * strain), 1e-10);
}

TEST(LinearElastic, UniaxialStressPatch) {
  const double e = 1.2e6, nu = 0.3;
  const LinearElastic m(e, nu);
  MaterialPointState state = m.initial_state(8.9, 0.0);
  double strain = 0.0;
  for (int step = 0; step < 100; ++step) {
    m.update(diagonal_rate(1e-5, -nu * 1e-5, -nu * 1e-5), 1.0, state);
    strain += 1e-5;
  }
  EXPECT_LT(relative_error(state.stress[0], e * strain), 1e-10);
  EXPECT_LT(std::abs(state.stress[1]), 1e-10 * state.stress[0]);
  EXPECT_LT(std::abs(state.stress[2]), 1e-10 * state.stress[0]);
}

TEST(LinearElastic, RigidRotationRotatesStressAndKeepsInvariants) {
  const LinearElastic m(1.2e6, 0.3);
  MaterialPointState state = m.initial_state(8.9, 0.0);
  state.stress = {{300.0, -120.0, 50.0, 40.0, -70.0, 90.0}};
  const SymmetricTensor initial = state.stress;
  const Eigen::Vector3d axis(1.0, 2.0, 3.0);
  const double angle = std::numbers::pi / 2;
  const int steps = 200;
  const double dt = 1e-3;
  const Mat3 l = spin_rate(axis, angle / (steps * dt));
  const Eigen::Vector3d i0 = invariants(initial);
  for (int step = 0; step < steps; ++step) {
    m.update(l, dt, state);
    const Eigen::Vector3d i = invariants(state.stress);
    for (int k = 0; k < 3; ++k) EXPECT_LT(relative_error(i[k], i0[k]), 1e-12) << "invariant " << k;
  }
  const Mat3 r = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  const Mat3 expected = r * initial.to_matrix() * r.transpose();
  const double error = (state.stress.to_matrix() - expected).norm() / expected.norm();
  EXPECT_LT(error, 1e-4);
}

TEST(LinearElastic, QuarterTurnAboutZSwapsNormalStresses) {
  const LinearElastic m(1.0, 0.25);
  MaterialPointState state = m.initial_state(1.0, 0.0);
  state.stress = {{2.0, -1.0, 0.5, 0.0, 0.0, 0.3}};
  const int steps = 1000;
  const Mat3 l = spin_rate({0, 0, 1}, std::numbers::pi / 2);
  for (int step = 0; step < steps; ++step) m.update(l, 1.0 / steps, state);
  EXPECT_NEAR(state.stress[0], -1.0, 1e-5);
  EXPECT_NEAR(state.stress[1], 2.0, 1e-5);
  EXPECT_NEAR(state.stress[2], 0.5, 1e-12);
  EXPECT_NEAR(state.stress[5], -0.3, 1e-5);
}

TEST(LinearElastic, WaveSpeedOfTheSeedBar) {
  // Seed App. 2 bar: rho = 1, E = 1e6 and a 1-D (nu = 0) bar give c = 1000.
  const LinearElastic m(1e6, 0.0);
  EXPECT_NEAR(m.wave_speed(m.initial_state(1.0, 0.0)), 1000.0, 1e-9);
  const LinearElastic n(1.2e6, 0.3);
  const double p_wave = n.elasticity().p_wave_modulus();
  EXPECT_NEAR(n.wave_speed(n.initial_state(8.9, 0.0)), std::sqrt(p_wave / 8.9), 1e-9);
  EXPECT_NEAR(p_wave, 1.2e6 * 0.7 / (1.3 * 0.4), 1e-6);
}

// --- J2 plasticity ---------------------------------------------------------

TEST(J2Plasticity, UniaxialStrainElasticPerfectlyPlasticThenElasticUnloading) {
  const double sy = 2000.0;
  const J2Plasticity m(1.2e6, 0.3, sy, 0.0);
  const double lambda = m.elasticity().lambda;
  const double mu = m.elasticity().shear_modulus;
  const double k = m.elasticity().bulk_modulus();
  const double yield_strain = sy / (2 * mu);  // sigma_xx - sigma_yy = 2 mu eps
  MaterialPointState state = m.initial_state(8.9, 0.0);
  double strain = 0.0;
  const double de = yield_strain / 37.3;  // the yield point falls inside a step
  bool yielded = false;
  for (int step = 0; step < 150; ++step) {
    m.update(diagonal_rate(de, 0, 0), 1.0, state);
    strain += de;
    const double q = von_mises_stress(state.stress);
    if (strain < yield_strain) {
      EXPECT_LT(relative_error(q, 2 * mu * strain), 1e-10);
      EXPECT_EQ(state.plastic_strain, 0.0);
    } else {
      yielded = true;
      EXPECT_LT(relative_error(q, sy), 1e-6);
      EXPECT_LT(relative_error(state.plastic_strain, 2.0 / 3.0 * (strain - yield_strain)), 1e-9);
      const double sxx = (lambda + 2 * mu) * yield_strain + k * (strain - yield_strain);
      EXPECT_LT(relative_error(state.stress[0], sxx), 1e-9);
    }
  }
  ASSERT_TRUE(yielded);

  // Unloading: elastic with slope lambda + 2 mu until the deviator reverses
  // by 2 sigma_y, then yield in compression.
  const double ep = state.plastic_strain;
  const double sxx_peak = state.stress[0];
  double unloaded = 0.0;
  for (int step = 0; step < 70; ++step) {
    m.update(diagonal_rate(-de, 0, 0), 1.0, state);
    unloaded += de;
    if (2 * mu * unloaded < 2 * sy) {
      EXPECT_LT(relative_error(state.stress[0], sxx_peak - (lambda + 2 * mu) * unloaded), 1e-9);
      EXPECT_EQ(state.plastic_strain, ep);
    } else {
      EXPECT_LT(relative_error(state.stress[0] - state.stress[1], -sy), 1e-6);
      EXPECT_GT(state.plastic_strain, ep);
    }
  }
}

TEST(J2Plasticity, UniaxialStrainHardeningSlopeIsTheElastoplasticTangent) {
  const double sy = 2000.0, h = 5e4;
  const J2Plasticity m(1.2e6, 0.3, sy, h);
  const double mu = m.elasticity().shear_modulus;
  const double k = m.elasticity().bulk_modulus();
  const double tangent = k + 4.0 / 3.0 * mu * h / (3 * mu + h);
  MaterialPointState state = m.initial_state(8.9, 0.0);
  const double de = sy / (2 * mu) / 20.5;
  double previous = 0.0;
  for (int step = 0; step < 100; ++step) {
    previous = state.stress[0];
    m.update(diagonal_rate(de, 0, 0), 1.0, state);
    if (state.plastic_strain > 0.0) {
      EXPECT_LT(relative_error(von_mises_stress(state.stress), m.flow_stress(state.plastic_strain)),
                1e-10);
    }
  }
  EXPECT_LT(relative_error((state.stress[0] - previous) / de, tangent), 1e-9);
}

TEST(J2Plasticity, UniaxialStressFollowsTheBilinearCurve) {
  const double e = 1.2e6, nu = 0.3, sy = 2000.0;
  for (const double h : {0.0, 5e4}) {
    const J2Plasticity m(e, nu, sy, h);
    const double tangent = e * h / (e + h);
    MaterialPointState state = m.initial_state(8.9, 0.0);
    const double de = sy / e / 23.7;
    double strain = 0.0;
    for (int step = 0; step < 120; ++step) {
      state = uniaxial_stress_step(m, state, de, nu);
      strain += de;
      const double expected = strain < sy / e ? e * strain : sy + tangent * (strain - sy / e);
      EXPECT_LT(relative_error(state.stress[0], expected), 1e-9) << "H = " << h;
      EXPECT_LT(std::abs(state.stress[1]), 1e-9 * sy);
      EXPECT_LT(std::abs(state.stress[2]), 1e-9 * sy);
    }
    // Unloading is elastic with slope E.
    const double peak = state.stress[0];
    const double ep = state.plastic_strain;
    for (int step = 0; step < 10; ++step) state = uniaxial_stress_step(m, state, -de, nu);
    EXPECT_LT(relative_error(state.stress[0], peak - e * 10 * de), 1e-9);
    EXPECT_EQ(state.plastic_strain, ep);
  }
}

TEST(J2Plasticity, RigidRotationKeepsAYieldedStateOnTheSurface) {
  const double sy = 2000.0;
  const J2Plasticity m(1.2e6, 0.3, sy, 1e4);
  MaterialPointState state = m.initial_state(8.9, 0.0);
  const Mat3 shear = [] {
    Mat3 l = Mat3::Zero();
    l(0, 1) = 1e-4;
    return l;
  }();
  for (int step = 0; step < 100; ++step) m.update(shear, 1.0, state);
  ASSERT_GT(state.plastic_strain, 0.0);
  const double ep = state.plastic_strain;
  const double q = von_mises_stress(state.stress);
  for (int step = 0; step < 500; ++step) m.update(spin_rate({1, -1, 2}, 3e-3), 1.0, state);
  // Round-off may push the rotated state an ulp outside the surface.
  EXPECT_LT(relative_error(state.plastic_strain, ep), 1e-12);
  EXPECT_LT(relative_error(von_mises_stress(state.stress), q), 1e-12);
}

TEST(J2Plasticity, WorkDoneEqualsStoredPlusDissipated) {
  const J2Plasticity m(1.2e6, 0.3, 2000.0, 5e4);
  MaterialPointState state = m.initial_state(8.9, 0.0);
  double work = 0.0;
  const double de = 2e-6;  // yields near step 1100 of 2000
  for (int step = 0; step < 3000; ++step) {
    const double rate = step < 2000 ? de : -de;
    const double before = state.stress[0];
    m.update(diagonal_rate(rate, 0, 0), 1.0, state);
    work += 0.5 * (before + state.stress[0]) * rate;  // sigma : D dt, only xx is strained
  }
  ASSERT_GT(state.plastic_strain, 0.0);
  const double balance = m.stored_energy_density(state) + m.dissipated_energy_density(state);
  EXPECT_LT(relative_error(balance, work), 1e-3);
}

// --- Ideal gas -------------------------------------------------------------

TEST(IdealGas, AdiabaticCompressionKeepsPVGammaAndEnergyIsMinusPdV) {
  const IdealGas gas;  // gamma = 1.4
  const double gamma = gas.gamma();
  const double mass = 2.5, rho0 = 0.5, p0 = 1e4;
  MaterialPointState state = gas.initial_state(rho0, p0);
  const double v0 = mass / rho0;
  const double e0 = state.internal_energy;
  EXPECT_LT(relative_error(-state.stress[0], p0), 1e-14);

  // Uniaxial compression to half the volume, the solver owning the density.
  const int steps = 400;
  const double dt = 1e-2;
  const double rate = (std::pow(0.5, 1.0 / steps) - 1.0) / dt;
  const Mat3 l = diagonal_rate(rate, 0, 0);
  double jacobian = 1.0;
  double pdv_work = 0.0;
  for (int step = 0; step < steps; ++step) {
    const double p_before = -state.stress[0];
    const double v_before = jacobian * v0;
    jacobian *= (Mat3::Identity() + dt * l).determinant();
    state.density = rho0 / jacobian;
    gas.update(l, dt, state);
    const double p = -state.stress[0];
    pdv_work -= 0.5 * (p_before + p) * (jacobian * v0 - v_before);
    EXPECT_LT(relative_error(p * std::pow(jacobian, gamma), p0), 1e-3);
    EXPECT_EQ(state.stress[1], state.stress[0]);
    EXPECT_EQ(state.stress[3], 0.0);
  }
  EXPECT_NEAR(jacobian, 0.5, 1e-12);
  const double p = -state.stress[0];
  EXPECT_LT(relative_error(p * std::pow(0.5, gamma), p0), 1e-5);

  // Energy: the change equals -integral P dV along the exact adiabat.
  const double v1 = 0.5 * v0;
  const double exact_work =
      p0 * std::pow(v0, gamma) * (std::pow(v1, 1 - gamma) - std::pow(v0, 1 - gamma)) / (gamma - 1);
  const double energy_change = mass * (state.internal_energy - e0);
  EXPECT_LT(relative_error(energy_change, exact_work), 1e-5);
  EXPECT_LT(relative_error(energy_change, pdv_work), 1e-12);
  EXPECT_LT(relative_error(gas.stored_energy_density(state) * v1, mass * state.internal_energy),
            1e-12);

  // Expanding back is reversible.
  for (int step = 0; step < steps; ++step) {
    const Mat3 back = diagonal_rate(-rate / (1 + rate * dt), 0, 0);
    jacobian *= (Mat3::Identity() + dt * back).determinant();
    state.density = rho0 / jacobian;
    gas.update(back, dt, state);
  }
  EXPECT_NEAR(jacobian, 1.0, 1e-12);
  EXPECT_LT(relative_error(state.internal_energy, e0), 1e-10);
}

TEST(IdealGas, SimpleShearDoesNoWorkAndSpinStaysOnTheAdiabat) {
  const IdealGas gas(5.0 / 3.0);
  MaterialPointState state = gas.initial_state(1.0, 3.0);
  const double e0 = state.internal_energy;
  Mat3 shear = Mat3::Zero();
  shear(0, 1) = 0.3;  // det(I + L dt) = 1 exactly: no volume change
  const double dt = 1e-3;
  for (int step = 0; step < 100; ++step) {
    state.density /= (Mat3::Identity() + dt * shear).determinant();
    gas.update(shear, dt, state);
  }
  EXPECT_EQ(state.internal_energy, e0);
  EXPECT_LT(relative_error(-state.stress[2], 3.0), 1e-14);
  for (int k = 3; k < 6; ++k) EXPECT_EQ(state.stress[k], 0.0);

  // A spin changes det(I + L dt) by O(dt^2): whatever volume the solver
  // books, the gas follows the adiabat through it and stays isotropic.
  const Mat3 spin = spin_rate({0, 1, 1}, 2.0);
  for (int step = 0; step < 100; ++step) {
    state.density /= (Mat3::Identity() + dt * spin).determinant();
    gas.update(spin, dt, state);
  }
  ASSERT_LT(state.density, 1.0 - 1e-5);
  const double p = -state.stress[0];
  EXPECT_LT(relative_error(p / std::pow(state.density, gas.gamma()), 3.0), 1e-10);
  EXPECT_EQ(state.stress[1], state.stress[0]);
  for (int k = 3; k < 6; ++k) EXPECT_EQ(state.stress[k], 0.0);
}

TEST(IdealGas, WaveSpeedAndInitialState) {
  const IdealGas gas;
  const MaterialPointState state = gas.initial_state(0.2, 5e3);
  EXPECT_LT(relative_error(gas.wave_speed(state), std::sqrt(1.4 * 5e3 / 0.2)), 1e-14);
  EXPECT_LT(relative_error(gas.pressure(0.2, state.internal_energy), 5e3), 1e-14);
  EXPECT_EQ(gas.wave_speed(gas.initial_state(0.2, 0.0)), 0.0);
  EXPECT_THROW((void)gas.initial_state(0.2, -1.0), pbms::Error);
  EXPECT_THROW((void)gas.initial_state(0.0, 1.0), pbms::Error);
}

// --- Registry --------------------------------------------------------------

namespace {

std::string error_of(const std::string& style, const MaterialParameters& params) {
  try {
    (void)MaterialRegistry::create(style, params);
  } catch (const pbms::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(MaterialRegistry, CreatesEveryBuiltInStyle) {
  EXPECT_EQ(
      MaterialRegistry::create("linear_elastic", {{"youngs_modulus", 1e6}, {"poisson_ratio", 0.3}})
          ->style(),
      "linear_elastic");
  const auto j2 = MaterialRegistry::create(
      "j2_plasticity", {{"youngs_modulus", 1e6}, {"poisson_ratio", 0.3}, {"yield_stress", 1e3}});
  EXPECT_EQ(j2->style(), "j2_plasticity");
  EXPECT_EQ(dynamic_cast<const J2Plasticity&>(*j2).flow_stress(1.0), 1e3);  // H defaults to 0
  const auto gas = MaterialRegistry::create("ideal_gas", {});
  EXPECT_EQ(dynamic_cast<const IdealGas&>(*gas).gamma(), 1.4);
  const auto styles = MaterialRegistry::styles();
  EXPECT_EQ(styles, (std::vector<std::string>{"cubic_j2_plasticity", "ideal_gas", "j2_plasticity",
                                              "linear_elastic"}));
}

TEST(MaterialRegistry, ErrorsNameTheProblemAndWhatIsAccepted) {
  const std::string unknown = error_of("neo_hookean", {});
  EXPECT_NE(unknown.find("'neo_hookean'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("cubic_j2_plasticity, ideal_gas, j2_plasticity, linear_elastic"),
            std::string::npos);

  const std::string missing = error_of("linear_elastic", {{"poisson_ratio", 0.3}});
  EXPECT_NE(missing.find("missing parameter 'youngs_modulus'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("0 < youngs_modulus"), std::string::npos) << missing;

  const std::string range =
      error_of("linear_elastic", {{"youngs_modulus", 1e6}, {"poisson_ratio", 0.5}});
  EXPECT_NE(range.find("'poisson_ratio' = 0.5"), std::string::npos) << range;
  EXPECT_NE(range.find("-1 < poisson_ratio < 0.5"), std::string::npos) << range;

  const std::string typo = error_of(
      "j2_plasticity",
      {{"youngs_modulus", 1e6}, {"poisson_ratio", 0.3}, {"yield_stress", 1e3}, {"hardening", 1.0}});
  EXPECT_NE(typo.find("unknown parameter 'hardening'"), std::string::npos) << typo;
  EXPECT_NE(typo.find("hardening_modulus"), std::string::npos) << typo;

  EXPECT_NE(error_of("ideal_gas", {{"gamma", 1.0}}).find("1 < gamma"), std::string::npos);
  EXPECT_NE(error_of("ideal_gas", {{"gamma", std::nan("")}}).find("gamma"), std::string::npos);
  EXPECT_NE(error_of("j2_plasticity", {{"youngs_modulus", 1e6},
                                       {"poisson_ratio", 0.3},
                                       {"yield_stress", 1e3},
                                       {"hardening_modulus", -1.0}})
                .find("0 <= hardening_modulus"),
            std::string::npos);
  EXPECT_THROW(LinearElastic(-1.0, 0.3), pbms::Error);
}

TEST(MaterialRegistry, AcceptsNewStylesOnce) {
  MaterialRegistry::add("test_stiff_gas", [](const MaterialParameters& p) {
    ParameterReader reader("test_stiff_gas", p);
    const double gamma = reader.required("gamma", ParameterRange::above(1.0));
    reader.reject_unknown();
    return std::make_unique<IdealGas>(gamma);
  });
  EXPECT_EQ(MaterialRegistry::create("test_stiff_gas", {{"gamma", 3.0}})->style(), "ideal_gas");
  EXPECT_THROW(MaterialRegistry::add("linear_elastic", LinearElastic::create), pbms::Error);
}

// --- Cubic J2 plasticity ---------------------------------------------------

namespace {

// Copper-like: the Sutton-Chen mesoparticle crystal's constants at 298 K in
// GPa (docs/hierarchy.md), anisotropy 2 C44 / (C11 - C12) = 2.9.
const CubicElasticity kCopperLike{167.1, 119.0, 70.3};

// Gamma_ik = C_ijkl n_j n_l, column k read off the stress of the strain
// sym(e_k n).
double largest_christoffel_eigenvalue(const CubicElasticity& c, const Eigen::Vector3d& n) {
  Mat3 christoffel;
  for (int k = 0; k < 3; ++k) {
    Mat3 strain = Mat3::Zero();
    strain.col(k) += 0.5 * n;
    strain.row(k) += 0.5 * n.transpose();
    christoffel.col(k) = c.stress_for(SymmetricTensor::from_matrix(strain)).to_matrix() * n;
  }
  return Eigen::SelfAdjointEigenSolver<Mat3>(christoffel).eigenvalues()(2);
}

Mat3 random_gradient(std::mt19937& rng, double size) {
  std::uniform_real_distribution<double> u(-size, size);
  Mat3 l;
  for (int i = 0; i < 9; ++i) l(i / 3, i % 3) = u(rng);
  return l;
}

}  // namespace

// With C44 = (C11 - C12) / 2 the crystal is isotropic and C : n is parallel
// to n: the cutting plane must stop after its first pass at the closed-form
// radial return, for any path (spin included).
TEST(CubicJ2Plasticity, IsotropicStiffnessReproducesTheRadialReturn) {
  const double e = 1.2e6, nu = 0.3, sy = 2000.0, h = 3e4;
  const IsotropicElasticity iso = IsotropicElasticity::from_youngs_modulus_and_poisson_ratio(e, nu);
  const CubicJ2Plasticity cubic(
      {iso.lambda + 2.0 * iso.shear_modulus, iso.lambda, iso.shear_modulus}, sy, h);
  const J2Plasticity j2(e, nu, sy, h);
  MaterialPointState a = j2.initial_state(8.9, 0.0);
  MaterialPointState b = a;
  std::mt19937 rng(7);
  for (int step = 0; step < 400; ++step) {
    const Mat3 l = random_gradient(rng, 4e-4);
    j2.update(l, 1.0, a);
    cubic.update(l, 1.0, b);
  }
  ASSERT_GT(a.plastic_strain, 0.01);
  EXPECT_LT(relative_error(b.plastic_strain, a.plastic_strain), 1e-11);
  for (int c = 0; c < 6; ++c) EXPECT_NEAR(b.stress[c], a.stress[c], 1e-10 * sy) << c;
}

// Pulled along a cube axis with free sides, the crystal answers with
// E<100> = (C11 - C12)(C11 + 2 C12)/(C11 + C12) and contracts sideways by
// nu<100> = C12 / (C11 + C12) (e.g. Nye, Physical Properties of Crystals).
TEST(CubicJ2Plasticity, UniaxialStressAlongACubeAxisHasTheTextbookModulus) {
  const double c11 = kCopperLike.c11, c12 = kCopperLike.c12;
  const double e100 = (c11 - c12) * (c11 + 2 * c12) / (c11 + c12);
  const CubicJ2Plasticity m(kCopperLike, 1e3, 0.0);
  MaterialPointState state = m.initial_state(8.9, 0.0);
  const double de = 1e-5;
  for (int step = 1; step <= 20; ++step) {
    const MaterialPointState next = uniaxial_stress_step(m, state, de, c12 / (c11 + c12));
    EXPECT_LT(relative_error(next.stress[0], e100 * step * de), 1e-9);
    EXPECT_LT(std::abs(next.stress[1]), 1e-12 * e100);
    state = next;
  }
}

// Pure shear in the cube planes: C : n stays along n (C44), so the return is
// exact in one pass and the shear stress levels off at sigma_y / sqrt(3).
TEST(CubicJ2Plasticity, PureShearLevelsOffAtTheShearYieldStress) {
  const double sy = 2.0;
  const CubicJ2Plasticity m(kCopperLike, sy, 0.0);
  MaterialPointState state = m.initial_state(8.9, 0.0);
  Mat3 l = Mat3::Zero();
  l(0, 1) = l(1, 0) = 1e-4;  // eps_xy grows by 1e-4 a step
  for (int step = 1; step <= 300; ++step) {
    m.update(l, 1.0, state);
    const double elastic = 2.0 * kCopperLike.c44 * 1e-4 * step;
    EXPECT_NEAR(state.stress[5], std::min(elastic, sy / std::sqrt(3.0)), 1e-12 * sy) << step;
  }
}

// From random yielded states under random increments the return ends on the
// yield surface, and keeps the elastic trial pressure (isochoric flow).
TEST(CubicJ2Plasticity, ReturnEndsOnTheSurfaceWithTheTrialPressure) {
  const double sy = 1.5, h = 4.0;
  const CubicJ2Plasticity m(kCopperLike, sy, h);
  const CubicJ2Plasticity elastic_only(kCopperLike, 1e30, 0.0);
  std::mt19937 rng(11);
  MaterialPointState state = m.initial_state(8.9, 0.0);
  int yielded = 0;
  for (int step = 0; step < 300; ++step) {
    const Mat3 l = random_gradient(rng, 6e-3);
    MaterialPointState trial = state;
    elastic_only.update(l, 1.0, trial);
    const double ep = state.plastic_strain;
    m.update(l, 1.0, state);
    EXPECT_NEAR(state.stress.trace(), trial.stress.trace(),
                1e-12 * std::abs(trial.stress.trace()) + 1e-14);
    if (state.plastic_strain > ep) {
      ++yielded;
      EXPECT_LT(relative_error(von_mises_stress(state.stress), m.flow_stress(state.plastic_strain)),
                1e-11);
    }
  }
  EXPECT_GT(yielded, 100);
}

TEST(CubicJ2Plasticity, WorkDoneEqualsStoredPlusDissipated) {
  const CubicJ2Plasticity m(kCopperLike, 1.0, 5.0);
  MaterialPointState state = m.initial_state(8.9, 0.0);
  double work = 0.0;
  const double de = 1e-5;  // (C11 - C12) eps_xx reaches sigma_y near step 2100
  for (int step = 0; step < 6000; ++step) {
    const double rate = step < 4000 ? de : -de;
    const double before = state.stress[0];
    m.update(diagonal_rate(rate, 0, 0), 1.0, state);
    work += 0.5 * (before + state.stress[0]) * rate;
  }
  ASSERT_GT(state.plastic_strain, 0.0);
  const double balance = m.stored_energy_density(state) + m.dissipated_energy_density(state);
  EXPECT_LT(relative_error(balance, work), 1e-3);
}

// The time step needs the fastest wave in any direction: the largest
// eigenvalue of the Christoffel matrix C_ijkl n_j n_l over many directions
// must not exceed the modulus wave_speed uses, and must reach it. Copper-like
// anisotropy (> 1) puts the fastest wave along <111>, one below 1 along <100>.
TEST(CubicJ2Plasticity, WaveSpeedIsTheFastestLongitudinalWave) {
  for (const CubicElasticity& c : {kCopperLike, CubicElasticity{200.0, 100.0, 30.0}}) {
    const CubicJ2Plasticity m(c, 1.0, 0.0);
    const double rho = 8.9;
    const double bound = std::pow(m.wave_speed(m.initial_state(rho, 0.0)), 2) * rho;
    std::mt19937 rng(3);
    std::normal_distribution<double> g;
    double fastest = 0.0;
    for (int k = 0; k < 4000; ++k) {
      Eigen::Vector3d n(g(rng), g(rng), g(rng));
      if (k == 0) n = {1, 1, 1};
      if (k == 1) n = {1, 0, 0};
      n.normalize();
      fastest = std::max(fastest, largest_christoffel_eigenvalue(m.elasticity(), n));
    }
    EXPECT_LE(fastest, bound * (1 + 1e-12)) << c.c44;
    EXPECT_GT(fastest, bound * (1 - 1e-12)) << c.c44;
  }
}

// j2_plasticity with a zener_ratio: the crystal keeps the given [100] pull
// (E<100>, nu<100> by the textbook formulas above) and has that anisotropy.
TEST(CubicJ2Plasticity, AZenerRatioMakesJ2ACubicCrystalWithTheSamePull) {
  const double e = 62.0, nu = 0.416, zener = 2.9;
  const auto m = MaterialRegistry::create("j2_plasticity", {{"youngs_modulus", e},
                                                            {"poisson_ratio", nu},
                                                            {"yield_stress", 9.7},
                                                            {"zener_ratio", zener}});
  const CubicElasticity& c = dynamic_cast<const CubicJ2Plasticity&>(*m).elasticity();
  EXPECT_EQ(m->style(), "j2_plasticity");  // errors name the kind the user wrote
  EXPECT_LT(relative_error((c.c11 - c.c12) * (c.c11 + 2 * c.c12) / (c.c11 + c.c12), e), 1e-14);
  EXPECT_LT(relative_error(c.c12 / (c.c11 + c.c12), nu), 1e-14);
  EXPECT_LT(relative_error(2 * c.c44 / (c.c11 - c.c12), zener), 1e-14);
  const auto iso = MaterialRegistry::create(
      "j2_plasticity", {{"youngs_modulus", e}, {"poisson_ratio", nu}, {"yield_stress", 9.7}});
  EXPECT_NE(dynamic_cast<const J2Plasticity*>(iso.get()), nullptr);
  EXPECT_NE(error_of("j2_plasticity", {{"youngs_modulus", e},
                                       {"poisson_ratio", nu},
                                       {"yield_stress", 9.7},
                                       {"zener_ratio", 0.0}})
                .find("0 < zener_ratio"),
            std::string::npos);
}

TEST(CubicJ2Plasticity, RefusesAnUnstableCrystal) {
  const std::string msg = error_of("cubic_j2_plasticity",
                                   {{"c11", 100}, {"c12", 120}, {"c44", 50}, {"yield_stress", 1}});
  EXPECT_NE(msg.find("not a stable cubic crystal"), std::string::npos) << msg;
  EXPECT_NE(msg.find("c11 > c12"), std::string::npos) << msg;
}

// A material kind's published bounds are the ones its kernel enforces: every
// real key of every built-in style is refused by create() just outside its
// schema range and on an exclusive bound, and accepted just inside.
TEST(MaterialKinds, SchemaBoundsAreTheKernelsOwn) {
  for (const auto& kind : MaterialRegistry::specs()) {
    MaterialParameters valid;
    for (const auto& p : kind.params) {
      if (p.name == "density") continue;
      if (p.default_value) valid[p.name] = p.default_value->as<double>();
    }
    if (kind.kind == "linear_elastic" || kind.kind == "j2_plasticity") {
      valid["youngs_modulus"] = 1e6;
    }
    if (kind.kind == "j2_plasticity" || kind.kind == "cubic_j2_plasticity") {
      valid["yield_stress"] = 1e3;
    }
    if (kind.kind == "cubic_j2_plasticity") {
      valid["c11"] = 1.7e6;
      valid["c12"] = 1.2e6;
      valid["c44"] = 0.8e6;
    }
    ASSERT_NO_THROW((void)MaterialRegistry::create(kind.kind, valid)) << kind.kind;
    for (const auto& p : kind.params) {
      if (p.name == "density") continue;
      for (const auto& [bound, exclusive, outward] :
           {std::tuple{p.min, p.min_exclusive, -1.0}, std::tuple{p.max, p.max_exclusive, 1.0}}) {
        if (!bound) continue;
        MaterialParameters bad = valid;
        const double step = 1e-6 * std::max(1.0, std::abs(*bound));
        bad[p.name] = *bound + outward * step;
        EXPECT_THROW((void)MaterialRegistry::create(kind.kind, bad), pbms::Error)
            << kind.kind << "." << p.name << " just outside " << *bound;
        if (exclusive) {
          bad[p.name] = *bound;
          EXPECT_THROW((void)MaterialRegistry::create(kind.kind, bad), pbms::Error)
              << kind.kind << "." << p.name << " on its exclusive bound";
        }
      }
    }
  }
}
