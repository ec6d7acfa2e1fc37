// The hand-fitted Morse potential of the 8-atom copper mesoparticle
// (docs/dpd-morse-fit.md, configs/potentials/cu_cg_morse.yaml), checked with
// the real kernels on static crystals: equilibrium lattice constant, bulk
// modulus and cubic elastic constants.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "cu_cg_morse.hpp"
#include "kernels/fcc_crystal.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "pbms/units.hpp"

using namespace pbms::dpd;

namespace {

constexpr double kLattice = 7.23;  // Å
constexpr double kMass = 508.37;   // g/mol
constexpr double kGpaPerEvPerA3 = pbms::units::kBarPerEvPerA3 / pbms::units::kBarPerGPa;

// Potential energy (eV) of a crystal after the homogeneous strain
// x_a → (1 + strain[a]) x_a along the box axes.
double strained_energy(const FccCrystal& reference, const Vec3& strain) {
  FccCrystal crystal = reference;
  for (int a = 0; a < 3; ++a) {
    crystal.box.hi[a] *= 1.0 + strain[a];
    for (auto& x : crystal.particles.x) x[a] *= 1.0 + strain[a];
  }
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  HalfNeighbourList list(morse->cutoff(), 0.5);
  list.build(crystal.particles, crystal.box);
  return morse->compute(crystal.particles, list, Tally::kEnergyAndVirial).energy;
}

// d²W/dε² (eV/Å³) of the strain energy density along the given strain
// direction, by a central difference with ε = 1e-3 (truncation ~ε² C''', far
// below the tolerances below).
double strain_curvature(const FccCrystal& crystal, const Vec3& direction) {
  const double eps = 1e-3;
  const Vec3 plus{eps * direction[0], eps * direction[1], eps * direction[2]};
  const Vec3 minus{-plus[0], -plus[1], -plus[2]};
  const double e0 = strained_energy(crystal, {0.0, 0.0, 0.0});
  return (strained_energy(crystal, plus) + strained_energy(crystal, minus) - 2.0 * e0) /
         (eps * eps * crystal.box.volume());
}

// The fcc crystal with axes x' = [110], y' = [-110], z = [001]: body-centred
// tetragonal cells a/√2 × a/√2 × a of two particles. The orthogonal strain
// (ε, −ε, 0) of this box is the pure shear ε_xy = ε of the cubic axes.
FccCrystal rotated_fcc(int cells_xy, int cells_z) {
  const double side = kLattice / std::numbers::sqrt2;
  FccCrystal crystal;
  crystal.box.hi = {cells_xy * side, cells_xy * side, cells_z * kLattice};
  crystal.particles.mass_per_type = {kMass};
  std::int64_t id = 1;
  for (int k = 0; k < cells_z; ++k) {
    for (int j = 0; j < cells_xy; ++j) {
      for (int i = 0; i < cells_xy; ++i) {
        crystal.particles.add(id++, 0, {i * side, j * side, k * kLattice});
        crystal.particles.add(id++, 0, {(i + 0.5) * side, (j + 0.5) * side, (k + 0.5) * kLattice});
      }
    }
  }
  return crystal;
}

}  // namespace

TEST(DpdMorseCopperFit, EnergyIsMinimalAt723AngstromWithBulkModulus138Gpa) {
  // E per particle at a + h·k for k = −2..2, h = 0.002 Å.
  const FccCrystal crystal = fcc_crystal(4, 4, 4, kLattice, kMass);
  const double n = static_cast<double>(crystal.particles.size());
  const double h = 0.002;
  double e[5];
  for (int k = -2; k <= 2; ++k) {
    const double s = h * k / kLattice;
    e[k + 2] = strained_energy(crystal, {s, s, s}) / n;
  }
  const double slope = (e[0] - 8.0 * e[1] + 8.0 * e[3] - e[4]) / (12.0 * h);
  const double curvature =
      (-e[0] + 16.0 * e[1] - 30.0 * e[2] + 16.0 * e[3] - e[4]) / (12.0 * h * h);
  const double minimum = kLattice - slope / curvature;
  // V = a³/4 per particle, so B = V d²E/dV² = 4 E''(a) / (9 a) at the minimum.
  const double bulk_gpa = 4.0 * curvature / (9.0 * kLattice) * kGpaPerEvPerA3;
  std::printf("Morse Cu mesoparticle: E = %.5f eV/particle, minimum at a = %.6f Å, B = %.2f GPa\n",
              e[2], minimum, bulk_gpa);
  EXPECT_NEAR(minimum, kLattice, 1e-4);  // parameters rounded to 6 digits
  EXPECT_NEAR(bulk_gpa, 138.0, 0.2);
  EXPECT_NEAR(e[2], -19.7237, 1e-3);  // shifted Morse: 12 + 6 + 24 neighbours inside 10 Å
}

TEST(DpdMorseCopperFit, CubicElasticConstantsObeyTheCauchyRelation) {
  const FccCrystal cubic = fcc_crystal(4, 4, 4, kLattice, kMass);
  const double c11 = strain_curvature(cubic, {1.0, 0.0, 0.0});
  // Biaxial (ε, ε, 0): d²W/dε² = 2 (C11 + C12).
  const double c12 = 0.5 * strain_curvature(cubic, {1.0, 1.0, 0.0}) - c11;
  const FccCrystal rotated = rotated_fcc(6, 4);
  // Shear ε_xy = ε: W = 2 C44 ε².
  const double c44 = 0.25 * strain_curvature(rotated, {1.0, -1.0, 0.0});

  const double gpa = kGpaPerEvPerA3;
  const double e100 = (c11 - c12) * (c11 + 2.0 * c12) / (c11 + c12);
  // ρ in kg/m³ from g/mol/Å³: 1 g/mol/Å³ = 1.66053906660e3 kg/m³.
  const double density =
      4.0 * kMass / std::pow(kLattice, 3) * pbms::units::kGramPerCm3PerAmuPerA3 * 1e3;
  const double longitudinal = std::sqrt(c11 * gpa * 1e9 / density);
  const double bar_speed = std::sqrt(e100 * gpa * 1e9 / density);
  std::printf(
      "Morse Cu mesoparticle: C11 = %.2f, C12 = %.2f, C44 = %.2f, B = %.2f, E<100> = %.2f GPa; "
      "rho = %.1f kg/m^3, sqrt(C11/rho) = %.0f m/s, sqrt(E<100>/rho) = %.0f m/s\n",
      c11 * gpa, c12 * gpa, c44 * gpa, (c11 + 2.0 * c12) / 3.0 * gpa, e100 * gpa, density,
      longitudinal, bar_speed);
  // A central pair potential at zero pressure has C12 = C44 exactly.
  EXPECT_NEAR(c12 / c44, 1.0, 1e-4);
  EXPECT_NEAR((c11 + 2.0 * c12) / 3.0 * gpa, 138.0, 0.2);
  // The lattice sum Σ (φ'' − φ'/r) x⁴ / r² / (2Ω) over the 42 neighbours gives 185.80 GPa.
  EXPECT_NEAR(c11 * gpa, 185.80, 0.2);
}
