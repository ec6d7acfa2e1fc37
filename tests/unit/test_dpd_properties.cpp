// The in-process property calculators of the DPD crystal
// (dpd_driver/properties): elastic constants, isotherm and uniaxial strain, static and at
// 298 K, on the hand-fitted Morse copper mesoparticle (docs/dpd-morse-fit.md)
// and on a Sutton–Chen crystal, whose C12 ≠ C44 a pair potential cannot give.
//
// The static checks compare with independent finite differences of the
// energy, computed here on crystals built here. The DpdProperties tests take
// ~4 s together; DISABLED_DpdPropertiesLong (~40 s) checks the claims behind
// the thermal defaults: reported errors against the scatter over seeds, and
// 3 cells against 5.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "cu_cg_morse.hpp"
#include "kernels/fcc_crystal.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/sutton_chen.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"
#include "properties/elastic_constants.hpp"
#include "properties/isotherm.hpp"
#include "properties/uniaxial_strain.hpp"

using namespace pbms::dpd;
using namespace pbms::analysis;

namespace {

constexpr double kLattice = 7.23;  // Å
constexpr double kMass = 508.37;   // g/mol
constexpr double kRoomTemperature = 298.0;
constexpr double kGpaPerEvPerA3 = pbms::units::kBarPerEvPerA3 / pbms::units::kBarPerGPa;

// Sutton & Chen's (1990) copper (ε = 12.382 meV, a = 3.61 Å, n = 9, m = 6,
// c = 39.432), cut between the 3rd and 4th shells.
constexpr double kSuttonChenLattice = 3.61;
SuttonChen sutton_chen_copper() {
  return SuttonChen(0.012382, 3.61, 9.0, 6.0, 39.432, 4.9);
}

ThermalSettings room_temperature() {
  ThermalSettings t;
  t.temperature = kRoomTemperature;
  return t;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---- the independent static route: energies of crystals built here ----------

// Cubic fcc, or with x' = [110], y' = [−110], z = [001] (two particles per
// a/√2 × a/√2 × a cell), `cells` lattice constants or more per edge.
FccCrystal crystal_of(double a, int cells, bool rotated) {
  if (!rotated) return fcc_crystal(cells, cells, cells, a, kMass);
  const double side = a / std::numbers::sqrt2;
  const int across = static_cast<int>(std::ceil(cells * std::numbers::sqrt2));
  FccCrystal crystal;
  crystal.box.hi = {across * side, across * side, cells * a};
  crystal.particles.mass_per_type = {kMass};
  std::int64_t id = 1;
  for (int k = 0; k < cells; ++k) {
    for (int j = 0; j < across; ++j) {
      for (int i = 0; i < across; ++i) {
        crystal.particles.add(id++, 0, {i * side, j * side, k * a});
        crystal.particles.add(id++, 0, {(i + 0.5) * side, (j + 0.5) * side, (k + 0.5) * a});
      }
    }
  }
  return crystal;
}

// Potential energy per unit reference volume (eV/Å³) after x_a → (1 + e_a) x_a.
double energy_density(PairStyle& pair, const FccCrystal& reference, const Vec3& e) {
  FccCrystal crystal = reference;
  for (int a = 0; a < 3; ++a) {
    crystal.box.hi[a] *= 1.0 + e[a];
    for (auto& x : crystal.particles.x) x[a] *= 1.0 + e[a];
  }
  HalfNeighbourList list(pair.cutoff(), 0.0);
  list.build(crystal.particles, crystal.box);
  return pair.compute(crystal.particles, list, Tally::kEnergyAndVirial).energy /
         reference.box.volume();
}

// d²W/dε² along a strain direction, GPa, central difference with ε = 1e-4
// (truncation ~1e-8 relative, round-off ~1e-7 GPa). At zero stress this is
// the elastic modulus of that direction.
double energy_curvature(PairStyle& pair, const FccCrystal& crystal, const Vec3& direction) {
  const double h = 1e-4;
  const Vec3 plus{h * direction[0], h * direction[1], h * direction[2]};
  const Vec3 minus{-plus[0], -plus[1], -plus[2]};
  return (energy_density(pair, crystal, plus) + energy_density(pair, crystal, minus) -
          2.0 * energy_density(pair, crystal, {0.0, 0.0, 0.0})) /
         (h * h) * kGpaPerEvPerA3;
}

struct Cubic {
  double c11, c12, c44;
};

// Uniaxial → C11, biaxial (ε, ε, 0) → 2 (C11 + C12), shear of the rotated
// crystal (ε, −ε, 0) → 4 C44.
Cubic constants_from_energy(PairStyle& pair, double a, int cells) {
  const FccCrystal cubic = crystal_of(a, cells, false);
  const double c11 = energy_curvature(pair, cubic, {1.0, 0.0, 0.0});
  const double c12 = 0.5 * energy_curvature(pair, cubic, {1.0, 1.0, 0.0}) - c11;
  const double c44 = 0.25 * energy_curvature(pair, crystal_of(a, cells, true), {1.0, -1.0, 0.0});
  return {c11, c12, c44};
}

// −dE/dV (GPa) of the static cubic crystal at V/V0 = ratio, V0 of lattice a0.
double pressure_from_energy(PairStyle& pair, double a0, double ratio) {
  const FccCrystal crystal = crystal_of(a0 * std::cbrt(ratio), 4, false);
  const double h = 1e-4;  // linear strain; dV/V = 3h to first order
  const double up = energy_density(pair, crystal, {h, h, h});
  const double down = energy_density(pair, crystal, {-h, -h, -h});
  const double dv_over_v = std::pow(1.0 + h, 3) - std::pow(1.0 - h, 3);
  return -(up - down) / dv_over_v * kGpaPerEvPerA3;
}

void print(const char* label, const ElasticConstants& c, double seconds) {
  std::printf(
      "%s: C11 = %.2f +- %.2f, C12 = %.2f +- %.2f, C44 = %.2f +- %.2f, E<100> = %.2f +- %.2f, "
      "B = %.2f +- %.2f, P = %.4f +- %.4f GPa (%.2f s)\n",
      label, c.c11, c.c11_error, c.c12, c.c12_error, c.c44, c.c44_error, c.youngs_modulus_100(),
      c.youngs_100_error, c.bulk_modulus(), c.bulk_modulus_error, c.pressure, c.pressure_error,
      seconds);
}

}  // namespace

TEST(DpdProperties, StaticMorseConstantsAreTheLatticeSums) {
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  const auto start = std::chrono::steady_clock::now();
  const ElasticConstants c = elastic_constants(*morse, {kLattice, 0, kMass}, ThermalSettings{});
  print("Morse, static, a = 7.23 Å", c, seconds_since(start));
  // docs/dpd-morse-fit.md: the lattice sums over the 42 neighbours.
  EXPECT_NEAR(c.c11 / 185.80, 1.0, 1e-3);
  EXPECT_NEAR(c.c12 / 114.10, 1.0, 1e-3);
  EXPECT_NEAR(c.c44 / 114.10, 1.0, 1e-3);
  EXPECT_NEAR(c.youngs_modulus_100() / 98.97, 1.0, 1e-3);
  EXPECT_NEAR(c.bulk_modulus() / 138.0, 1.0, 1e-3);
  // The Cauchy relation of a pair potential at zero pressure.
  EXPECT_NEAR(c.c12 / c.c44, 1.0, 1e-6);
  EXPECT_NEAR(c.pressure, 0.0, 1e-3);  // 7.23 Å is the minimum to 1e-6 Å
  EXPECT_EQ(c.c11_error, 0.0);
  EXPECT_EQ(c.c44_error, 0.0);
  EXPECT_EQ(c.pressure_error, 0.0);

  // Any cell count gives the same perfect crystal.
  const ElasticConstants larger =
      elastic_constants(*morse, {kLattice, 5, kMass}, ThermalSettings{});
  EXPECT_NEAR(larger.c11, c.c11, 1e-9 * c.c11);
  EXPECT_NEAR(larger.c44, c.c44, 1e-9 * c.c44);
}

TEST(DpdProperties, StaticSuttonChenConstantsMatchEnergyCurvatureWithC12NotC44) {
  SuttonChen sc = sutton_chen_copper();
  const double a0 = zero_pressure_lattice_constant(sc, {kSuttonChenLattice, 0, 63.546}, {});
  const auto start = std::chrono::steady_clock::now();
  const ElasticConstants c = elastic_constants(sc, {a0, 0, 63.546}, {});
  print("Sutton-Chen, static", c, seconds_since(start));
  const Cubic energy = constants_from_energy(sc, a0, 5);
  std::printf("  from the energy: C11 = %.3f, C12 = %.3f, C44 = %.3f GPa at a0 = %.6f Å\n",
              energy.c11, energy.c12, energy.c44, a0);
  // At zero pressure the stress–strain slopes are the energy curvatures.
  EXPECT_NEAR(c.pressure, 0.0, 1e-5);
  EXPECT_NEAR(c.c11 / energy.c11, 1.0, 1e-5);
  EXPECT_NEAR(c.c12 / energy.c12, 1.0, 1e-5);
  EXPECT_NEAR(c.c44 / energy.c44, 1.0, 1e-5);
  // The embedding term breaks the Cauchy relation: what a wrong shear (one
  // that missed the many-body part) would hide.
  EXPECT_GT(std::abs(c.c12 - c.c44), 0.2 * c.c44);
}

TEST(DpdProperties, StaticIsothermIsMinusEnergyDerivative) {
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  const CrystalSpec reference{kLattice, 0, kMass};
  for (const double ratio : {0.8, 0.9, 1.0, 1.05}) {
    const IsothermPoint p = isotherm_point(*morse, reference, {}, ratio);
    const double expected = pressure_from_energy(*morse, kLattice, ratio);
    std::printf("Morse, static: P(V/V0 = %.2f) = %.5f GPa, -dE/dV = %.5f GPa\n", ratio, p.pressure,
                expected);
    EXPECT_NEAR(p.pressure, expected, 1e-5 * std::max(1.0, std::abs(expected)));
    EXPECT_DOUBLE_EQ(p.lattice_constant, kLattice * std::cbrt(ratio));
    EXPECT_EQ(p.pressure_error, 0.0);
  }
  // docs/dpd-morse-fit.md: the minimum of E(a) lies at 7.230001 Å.
  EXPECT_NEAR(zero_pressure_lattice_constant(*morse, {7.3, 0, kMass}, {}), 7.230001, 2e-6);
}

TEST(DpdProperties, VolumeRatioAtPressureInvertsIsothermPoint) {
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  const CrystalSpec reference{kLattice, 0, kMass};
  for (const double target : {-3.0, 5.0, 30.0}) {
    const IsothermPoint found = volume_ratio_at_pressure(*morse, reference, {}, target);
    EXPECT_NEAR(found.pressure, target, 1e-5 * std::max(1.0, std::abs(target)));
    EXPECT_NEAR(isotherm_point(*morse, reference, {}, found.volume_ratio).pressure, target,
                1e-5 * std::max(1.0, std::abs(target)));
  }
  // Far beyond the spinodal in tension there is no state to find.
  EXPECT_THROW(volume_ratio_at_pressure(*morse, reference, {}, -60.0), pbms::Error);

  // At 298 K: the same seed makes the point reproducible, so the inversion
  // is checked against a fresh evaluation exactly, and against the target
  // to its tolerance, a quarter of the statistical error.
  const ThermalSettings hot = room_temperature();
  const auto start = std::chrono::steady_clock::now();
  const IsothermPoint found = volume_ratio_at_pressure(*morse, reference, hot, 5.0);
  const double seconds = seconds_since(start);
  const IsothermPoint again = isotherm_point(*morse, reference, hot, found.volume_ratio);
  std::printf("Morse, 298 K: P = 5 GPa at V/V0 = %.6f (P = %.5f +- %.5f GPa; %.2f s)\n",
              found.volume_ratio, found.pressure, found.pressure_error, seconds);
  EXPECT_DOUBLE_EQ(again.pressure, found.pressure);
  EXPECT_LE(std::abs(found.pressure - 5.0), 0.25 * found.pressure_error + 1e-6);
  EXPECT_GT(found.pressure_error, 0.0);
  EXPECT_LT(found.pressure_error, 0.05);
  // Thermal pressure at fixed volume: the hot crystal needs more volume.
  const double cold = volume_ratio_at_pressure(*morse, reference, {}, 5.0).volume_ratio;
  EXPECT_GT(found.volume_ratio, cold);
}

TEST(DpdProperties, MorseAt298KIsSlightlySofterThanStatic) {
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  const ThermalSettings hot = room_temperature();
  auto start = std::chrono::steady_clock::now();
  const double a = zero_pressure_lattice_constant(*morse, {kLattice, 0, kMass}, hot);
  const double zero_pressure_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const ElasticConstants c = elastic_constants(*morse, {a, 0, kMass}, hot);
  const double elastic_seconds = seconds_since(start);
  std::printf("Morse, 298 K: zero-pressure a = %.5f Å (%.2f s)\n", a, zero_pressure_seconds);
  print("Morse, 298 K, zero pressure", c, elastic_seconds);
  const ElasticConstants cold = elastic_constants(*morse, {kLattice, 0, kMass}, {});

  for (const double value : {c.c11, c.c12, c.c44, c.c11_error, c.c12_error, c.c44_error}) {
    EXPECT_TRUE(std::isfinite(value));
  }
  EXPECT_GT(c.c11, c.c12);
  // Errors: the defaults are meant to give ~0.1 %, far inside the 2–3 % that
  // the wave-speed checks need.
  EXPECT_GT(c.c11_error, 0.0);
  EXPECT_LT(c.c11_error, 0.003 * c.c11);
  EXPECT_LT(c.c12_error, 0.003 * c.c12);
  EXPECT_LT(c.c44_error, 0.003 * c.c44);
  EXPECT_LT(c.youngs_100_error, 0.005 * c.youngs_modulus_100());
  // The mesoparticle has 3 of the 24 degrees of freedom of its 8 atoms, so
  // its thermal softening is about an eighth of copper's (C11 ~5 % from 0 to
  // 298 K): of order 1 %, and not more than a few.
  for (const auto& [hot_value, cold_value] :
       {std::pair{c.c11, cold.c11}, std::pair{c.c44, cold.c44},
        std::pair{c.youngs_modulus_100(), cold.youngs_modulus_100()},
        std::pair{c.bulk_modulus(), cold.bulk_modulus()}}) {
    EXPECT_LT(hot_value, cold_value * 0.998);
    EXPECT_GT(hot_value, cold_value * 0.96);
  }
  // Thermal expansion: the 298 K crystal at 7.23 Å is under ~0.2 GPa.
  EXPECT_GT(a, kLattice * 1.0002);
  EXPECT_LT(a, kLattice * 1.002);
  // The rotated crystal of the elastic runs agrees that this is zero
  // pressure (O(ε²) and finite-size differences are ~0.001 GPa).
  EXPECT_NEAR(c.pressure, 0.0, 4.0 * c.pressure_error + 0.003);
}

// The combination of the four states, on stresses made here from a known
// cubic stiffness (Hooke's law in the rotated axes: the tetragonal strain
// ±ε along z gives σzz = ±C11 ε, σx'x' = σy'y' = ±C12 ε; the shear
// (±ε, ∓ε, 0) gives σx'x' = −σy'y' = ±2 C44 ε) on a common pressure, with a
// different stiffness in each block: the constants are the block means,
// their errors the standard errors of the block values.
TEST(DpdProperties, StrainStatesCombineToTheStiffnessThatMadeThem) {
  const double strain = 2e-3, p0 = 0.3;
  const std::vector<std::array<double, 3>> stiffness{{170.0, 120.0, 75.0},
                                                     {171.0, 119.0, 76.5},
                                                     {169.0, 121.5, 74.0},
                                                     {170.5, 120.5, 75.5},
                                                     {169.5, 119.0, 74.0}};
  std::array<std::vector<CauchyStress>, 4> states;
  for (const auto& [c11, c12, c44] : stiffness) {
    for (const StrainState state : kStrainStates) {
      const std::array<double, 3> e = strain_of(state, strain);
      CauchyStress s{-p0, -p0, -p0, 0.0, 0.0, 0.0};
      if (e[2] != 0.0) {
        s[0] += c12 * e[2];
        s[1] += c12 * e[2];
        s[2] += c11 * e[2];
      } else {
        s[0] += 2.0 * c44 * e[0];
        s[1] += 2.0 * c44 * e[1];
      }
      states[static_cast<std::size_t>(state)].push_back(s);
    }
  }
  const ElasticConstants c = elastic_constants_from_states(states, strain);
  // Mean and standard error of the five block values, computed here.
  const auto mean_error = [&](int k) {
    double mean = 0.0, variance = 0.0;
    for (const auto& b : stiffness) mean += b[k] / 5.0;
    for (const auto& b : stiffness) variance += (b[k] - mean) * (b[k] - mean) / 4.0;
    return std::pair{mean, std::sqrt(variance / 5.0)};
  };
  EXPECT_NEAR(c.c11, mean_error(0).first, 1e-9);
  EXPECT_NEAR(c.c12, mean_error(1).first, 1e-9);
  EXPECT_NEAR(c.c44, mean_error(2).first, 1e-9);
  EXPECT_NEAR(c.c11_error, mean_error(0).second, 1e-9);
  EXPECT_NEAR(c.c12_error, mean_error(1).second, 1e-9);
  EXPECT_NEAR(c.c44_error, mean_error(2).second, 1e-9);
  EXPECT_NEAR(c.pressure, p0, 1e-12);
  for (const StrainState state : kStrainStates) {
    EXPECT_EQ(strain_state_from_name(strain_state_name(state)), state);
  }
  EXPECT_THROW(strain_state_from_name("shear"), pbms::Error);
  states[3].pop_back();
  EXPECT_THROW(elastic_constants_from_states(states, strain), pbms::Error);
}

// The states sampled one by one, each with a pair style of its own (as the
// fit's requests on different rank groups do), combine to the bits of one
// elastic_constants call.
TEST(DpdProperties, StrainStatesSampledApartGiveTheSameConstants) {
  ThermalSettings hot = room_temperature();
  hot.equilibration_steps = 50;
  hot.sampling_steps = 100;
  const CrystalSpec crystal{kLattice, 0, kMass};
  const ElasticConstants whole = elastic_constants(*cu_cg_morse(), crystal, hot);
  std::array<std::vector<CauchyStress>, 4> states;
  for (const StrainState state : kStrainStates) {
    states[static_cast<std::size_t>(state)] =
        strain_state_stress(*cu_cg_morse(), crystal, hot, state);
    EXPECT_EQ(states[static_cast<std::size_t>(state)].size(),
              static_cast<std::size_t>(kStateBlocks));
  }
  const ElasticConstants apart = elastic_constants_from_states(states, elastic_strain(hot, 0.0));
  EXPECT_EQ(apart.c11, whole.c11);
  EXPECT_EQ(apart.c12, whole.c12);
  EXPECT_EQ(apart.c44, whole.c44);
  EXPECT_EQ(apart.c11_error, whole.c11_error);
  EXPECT_EQ(apart.c12_error, whole.c12_error);
  EXPECT_EQ(apart.c44_error, whole.c44_error);
  EXPECT_EQ(apart.youngs_100_error, whole.youngs_100_error);
  EXPECT_GT(whole.c44_error, 0.0);
}

// The static stress of uniaxial strain against the energy route: with
// W(e) the energy per reference volume after x → (1 + e) x, the force per
// reference area is W'(e), and with the lateral edges held that is also the
// Cauchy stress (the current area is the reference one), so the
// compressive stress of compression ε is −W'(−ε). W' by a central
// difference (h = 1e-5: truncation ~1e-10, round-off ~1e-8 relative to the
// stresses here).
TEST(DpdProperties, StaticUniaxialStrainIsMinusEnergyDerivative) {
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  const std::vector<double> compressions{1e-4, 0.02, 0.04, 0.05, 0.1};
  const std::vector<UniaxialStrainPoint> curve =
      uniaxial_strain_curve(*morse, {kLattice, 0, kMass}, {}, compressions);
  ASSERT_EQ(curve.size(), compressions.size());
  const FccCrystal cubic = crystal_of(kLattice, 4, false);
  // dW/de, GPa.
  const auto slope = [&](double e) {
    const double h = 1e-5;
    return (energy_density(*morse, cubic, {e + h, 0.0, 0.0}) -
            energy_density(*morse, cubic, {e - h, 0.0, 0.0})) /
           (2.0 * h) * kGpaPerEvPerA3;
  };
  // The curve is relative to the unstrained crystal's stress W'(0), ~0 at
  // 7.23 Å (the minimum of E(a) to 1e-6 Å).
  const double rest = slope(0.0);
  const double rho0 = 4.0 * kMass / std::pow(kLattice, 3) * 1660.5390666;  // kg/m^3
  for (const UniaxialStrainPoint& p : curve) {
    const double expected = -slope(-p.compression) + rest;
    std::printf("Morse, static, uniaxial %.4f: %.6f GPa (energy route %.6f), U_s = %.1f m/s\n",
                p.compression, p.stress, expected, p.shock_speed);
    EXPECT_NEAR(p.stress, expected, 1e-6 * std::max(1.0, expected));
    EXPECT_EQ(p.stress_error, 0.0);
    EXPECT_NEAR(p.shock_speed, std::sqrt(p.stress * 1e9 / (rho0 * p.compression)),
                1e-9 * p.shock_speed);
    EXPECT_NEAR(p.particle_velocity, p.compression * p.shock_speed, 1e-9 * p.particle_velocity);
  }
  // The weakest front travels at the longitudinal speed sqrt(C11/rho0), C11
  // the lattice sum of docs/dpd-morse-fit.md (185.80 GPa, to its 1e-3).
  EXPECT_NEAR(curve[0].shock_speed / std::sqrt(185.80e9 / rho0), 1.0, 1e-3);
  // Up to 4 % the Rayleigh speed grows with amplitude (a compression front
  // steepens). Past 1 − sqrt((10 Å / a)² − 1) = 4.45 % the (1, 1, 0) a
  // neighbours, 10.22 Å at rest, come inside the 10 Å cutoff, where the
  // shifted Morse force is attractive and jumps in: the stress at 5 % is
  // below the 4 % one's straight line, a kink of the model's cutoff that
  // the weak-shock prediction of an impact sees (docs/dpd-driver.md).
  EXPECT_GT(curve[1].shock_speed, curve[0].shock_speed);
  EXPECT_GT(curve[2].shock_speed, curve[1].shock_speed);
  EXPECT_LT(curve[3].shock_speed, curve[2].shock_speed);
  // Past it a wave splits; its leading front stays the 4 % shock.
  EXPECT_EQ(curve[3].front_speed, curve[2].shock_speed);
  EXPECT_EQ(curve[2].front_speed, curve[2].shock_speed);
}

// At 298 K the weak-front limit is the thermal C11: the Rayleigh speed at a
// compression of 2e-3 (elastic_constants' own strain) against
// sqrt(C11/rho0) within 1 %: the one-sided difference carries the O(ε)
// stiffening, +0.24 % at 2e-3 on the static curve (+2.4 % at 0.02), and the
// stress's 0.5 % error is 0.27 % in speed, 0.54 % at 2σ.
TEST(DpdProperties, UniaxialStrainAt298KStartsAtTheLongitudinalSpeed) {
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  const ThermalSettings hot = room_temperature();
  const double a = zero_pressure_lattice_constant(*morse, {kLattice, 0, kMass}, hot);
  const ElasticConstants c = elastic_constants(*morse, {a, 0, kMass}, hot);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<UniaxialStrainPoint> curve =
      uniaxial_strain_curve(*morse, {a, 0, kMass}, hot, {2e-3, 0.02});
  const double seconds = seconds_since(start);
  const double longitudinal = std::sqrt(c.c11 * 1e9 / fcc_density(a, kMass));
  std::printf(
      "Morse, 298 K, uniaxial: 2e-3 %.4f +- %.4f GPa, U_s %.1f m/s; 0.02 %.4f +- %.4f GPa, U_s "
      "%.1f m/s; sqrt(C11/rho) %.1f m/s (%.2f s)\n",
      curve[0].stress, curve[0].stress_error, curve[0].shock_speed, curve[1].stress,
      curve[1].stress_error, curve[1].shock_speed, longitudinal, seconds);
  EXPECT_NEAR(curve[0].shock_speed / longitudinal, 1.0, 1e-2);
  EXPECT_GT(curve[0].stress_error, 0.0);
  EXPECT_GT(curve[1].shock_speed, curve[0].shock_speed);
}

TEST(DpdProperties, InvalidSettingsAreRefused) {
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  const CrystalSpec crystal{kLattice, 0, kMass};
  EXPECT_THROW(elastic_constants(*morse, crystal, {}, -1e-3), pbms::Error);
  EXPECT_THROW(elastic_constants(*morse, crystal, {}, 0.1), pbms::Error);
  EXPECT_THROW(elastic_constants(*morse, {0.0, 0, kMass}, {}), pbms::Error);
  // 2 cells = 14.5 Å: a 10 Å cutoff sees two images of some neighbours.
  EXPECT_THROW(elastic_constants(*morse, {kLattice, 2, kMass}, {}), pbms::Error);
  EXPECT_THROW(isotherm_point(*morse, {kLattice, 3, kMass}, {}, 0.7), pbms::Error);
  EXPECT_THROW(isotherm_point(*morse, crystal, {}, 0.0), pbms::Error);
  ThermalSettings hot = room_temperature();
  EXPECT_THROW(isotherm_point(*morse, {kLattice, 0, 0.0}, hot, 1.0), pbms::Error);
  hot.sampling_steps = kStateBlocks - 1;
  EXPECT_THROW(isotherm_point(*morse, crystal, hot, 1.0), pbms::Error);
  hot = room_temperature();
  hot.temperature = -1.0;
  EXPECT_THROW(isotherm_point(*morse, crystal, hot, 1.0), pbms::Error);
  EXPECT_THROW(uniaxial_strain_curve(*morse, crystal, {}, {0.0}), pbms::Error);
  EXPECT_THROW(uniaxial_strain_curve(*morse, crystal, {}, {0.4}), pbms::Error);
  EXPECT_THROW(uniaxial_strain_curve(*morse, crystal, {}, {0.02, 0.01}), pbms::Error);
  // 3 cells (21.7 Å) compressed by 10 %: under twice the 10 Å cutoff.
  EXPECT_THROW(uniaxial_strain_curve(*morse, {kLattice, 3, kMass}, {}, {0.1}), pbms::Error);
}

// ~40 s: the claims behind the thermal defaults. Run with
// --gtest_also_run_disabled_tests --gtest_filter='DISABLED_DpdPropertiesLong.*'.
TEST(DISABLED_DpdPropertiesLong, ErrorsMatchSeedScatterAndThreeCellsSuffice) {
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  const CrystalSpec crystal{kLattice, 0, kMass};
  ThermalSettings hot = room_temperature();
  hot.sampling_steps = kElasticSamplingSteps;  // what dpd_elastic samples by default
  constexpr int kSeeds = 10;
  std::vector<double> c11, c44, reported_c11, reported_c44;
  for (int s = 0; s < kSeeds; ++s) {
    hot.seed = 100 + s;
    const ElasticConstants c = elastic_constants(*morse, crystal, hot);
    c11.push_back(c.c11);
    c44.push_back(c.c44);
    reported_c11.push_back(c.c11_error);
    reported_c44.push_back(c.c44_error);
  }
  const auto mean = [](const std::vector<double>& x) {
    double sum = 0.0;
    for (const double v : x) sum += v;
    return sum / static_cast<double>(x.size());
  };
  const auto scatter = [&](const std::vector<double>& x) {
    const double m = mean(x);
    double sum = 0.0;
    for (const double v : x) sum += (v - m) * (v - m);
    return std::sqrt(sum / static_cast<double>(x.size() - 1));
  };
  std::printf(
      "%d seeds: C11 = %.3f, scatter %.3f, mean reported error %.3f; C44 = %.3f, "
      "scatter %.3f, mean reported error %.3f GPa\n",
      kSeeds, mean(c11), scatter(c11), mean(reported_c11), mean(c44), scatter(c44),
      mean(reported_c44));
  // Both sides: an error estimate too large is as wrong as one too small. The
  // scatter of 10 values, s, follows sigma chi_9 / 3: s / sigma lies in
  // [0.45, 1.6] with probability 0.6 % below and 0.6 % above (chi-squared, 9
  // degrees of freedom); the mean of 10 reported errors adds ~7 %.
  EXPECT_GT(scatter(c11), 0.45 * mean(reported_c11));
  EXPECT_LT(scatter(c11), 1.6 * mean(reported_c11));
  EXPECT_GT(scatter(c44), 0.45 * mean(reported_c44));
  EXPECT_LT(scatter(c44), 1.6 * mean(reported_c44));

  hot.seed = 1;
  const ElasticConstants large = elastic_constants(*morse, {kLattice, 5, kMass}, hot);
  print("5 cells (640 particles in the rotated box)", large, 0.0);
  EXPECT_NEAR(large.c11, mean(c11), 0.1);
  EXPECT_NEAR(large.c44, mean(c44), 0.1);
}
