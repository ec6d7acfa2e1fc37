#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>

#include "kernels/fcc_crystal.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/lj_nm.hpp"
#include "kernels/morse.hpp"
#include "kernels/pair_style_registry.hpp"
#include "kernels/pair_table.hpp"
#include "kernels/sutton_chen.hpp"
#include "pbms/error.hpp"

using namespace pbms::dpd;

namespace {

constexpr double kCutoff = 8.0;
constexpr double kSkin = 1.0;

// ~100 particles at a density near the fcc mesoparticle crystal's, no two
// closer than min_distance, in a periodic box (or a free cluster).
DpdParticles random_configuration(const OrthogonalBox& box, int count, double min_distance,
                                  unsigned seed) {
  std::mt19937_64 rng(seed);
  DpdParticles p;
  p.mass_per_type = {508.37};
  std::uniform_real_distribution<double> u(0.0, 1.0);
  while (static_cast<int>(p.size()) < count) {
    Vec3 x{};
    for (int a = 0; a < 3; ++a) x[a] = box.lo[a] + u(rng) * box.length(a);
    bool clear = true;
    for (const auto& y : p.x) {
      const Vec3 d = box.minimum_image({x[0] - y[0], x[1] - y[1], x[2] - y[2]});
      if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < min_distance * min_distance) clear = false;
    }
    if (clear) p.add(static_cast<std::int64_t>(p.size()) + 1, 0, x);
  }
  return p;
}

OrthogonalBox periodic_box() {
  OrthogonalBox box;
  box.hi = {19.0, 20.0, 21.0};  // ≥ 2 (cutoff + skin) on every axis
  return box;
}

PairResult energy_forces(PairStyle& style, DpdParticles& p, const HalfNeighbourList& list) {
  p.zero_forces();
  return style.compute(p, list, Tally::kEnergyAndVirial);
}

// Forces against central differences of the total energy, every component of
// every particle, relative to the largest force component.
void expect_forces_are_minus_energy_gradient(PairStyle& style, const OrthogonalBox& box,
                                             unsigned seed) {
  DpdParticles p = random_configuration(box, 100, 3.6, seed);
  HalfNeighbourList list(style.cutoff(), kSkin);
  list.build(p, box);
  energy_forces(style, p, list);
  const std::vector<Vec3> force = p.f;
  double largest = 0.0;
  for (const auto& f : force)
    for (double c : f) largest = std::max(largest, std::abs(c));
  ASSERT_GT(largest, 0.0);

  const double h = 1e-5;
  double worst = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      const double x0 = p.x[i][a];
      p.x[i][a] = x0 + h;
      const double plus = energy_forces(style, p, list).energy;
      p.x[i][a] = x0 - h;
      const double minus = energy_forces(style, p, list).energy;
      p.x[i][a] = x0;
      worst = std::max(worst, std::abs(-(plus - minus) / (2.0 * h) - force[i][a]));
    }
  }
  EXPECT_LT(worst / largest, 1e-6) << style.name() << ": largest force " << largest;
}

// The virial against Σ_i x_i ⊗ f_i of a free cluster (no periodic images,
// so the two sums are the same), and against Σ r_ij ⊗ f_ij from the pair
// forces read back one pair at a time.
void expect_virial_is_sum_of_pair_outer_products(PairStyle& style) {
  OrthogonalBox box;
  box.hi = {20.0, 20.0, 20.0};
  box.periodic = {false, false, false};
  DpdParticles p = random_configuration(box, 100, 3.6, 11);
  HalfNeighbourList list(style.cutoff(), kSkin);
  list.build(p, box);
  const PairResult result = energy_forces(style, p, list);
  std::array<double, 6> expected{};
  const int row[6] = {0, 1, 2, 0, 0, 1};
  const int col[6] = {0, 1, 2, 1, 2, 2};
  double scale = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int c = 0; c < 6; ++c) expected[c] += p.x[i][row[c]] * p.f[i][col[c]];
  }
  for (double w : expected) scale = std::max(scale, std::abs(w));
  for (int c = 0; c < 6; ++c) {
    EXPECT_NEAR(result.virial[c], expected[c], 1e-9 * scale) << style.name() << " component " << c;
  }
}

// Periodic: the trace part of the virial is −dE/d(ln L) under a uniform
// dilation of box and positions, on each axis separately.
void expect_virial_is_minus_strain_derivative(PairStyle& style) {
  OrthogonalBox box = periodic_box();
  DpdParticles p = random_configuration(box, 100, 3.6, 5);
  HalfNeighbourList list(style.cutoff(), kSkin);
  list.build(p, box);
  const PairResult result = energy_forces(style, p, list);
  const double eps = 1e-6;
  for (int a = 0; a < 3; ++a) {
    double energy[2];
    for (int side = 0; side < 2; ++side) {
      const double stretch = side == 0 ? 1.0 + eps : 1.0 - eps;
      OrthogonalBox strained = box;
      strained.hi[a] = box.lo[a] + box.length(a) * stretch;
      DpdParticles q = p;
      for (auto& x : q.x) x[a] = box.lo[a] + (x[a] - box.lo[a]) * stretch;
      HalfNeighbourList strained_list(style.cutoff(), kSkin);
      strained_list.build(q, strained);
      energy[side] = energy_forces(style, q, strained_list).energy;
    }
    const double derivative = (energy[0] - energy[1]) / (2.0 * eps);
    EXPECT_NEAR(result.virial[a], -derivative, 1e-6 * std::abs(derivative) + 1e-9)
        << style.name() << " axis " << a;
  }
}

std::unique_ptr<PairStyle> make_morse(bool shift) {
  return std::make_unique<Morse>(0.8, 1.1, 5.11, kCutoff, shift);
}
std::unique_ptr<PairStyle> make_lj_nm() {
  return std::make_unique<LjNm>(0.4, 5.11, 12.0, 6.0, kCutoff, true);
}
std::unique_ptr<PairStyle> make_sutton_chen(double p = 0.5, double knee = 1.0,
                                            double flattening = 0.0) {
  return std::make_unique<SuttonChen>(0.0124, 3.61, 9.0, 6.0, 39.4, kCutoff, p, knee, flattening);
}

// A Morse table from 3 to 8 Å: rows every 0.01 Å, one row at 3.005 Å (so the
// rows are unevenly spaced) when `uneven`.
std::string write_morse_table(const std::string& name, bool uneven) {
  const Morse morse(0.8, 1.1, 5.11, kCutoff, false);
  const auto path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream out(path);
  out << "# r U F, Morse D0 0.8 alpha 1.1 r0 5.11\n\n";
  auto row = [&](double r) {
    const double decay = std::exp(-1.1 * (r - 5.11));
    out.precision(17);
    out << r << ' ' << 0.8 * decay * (decay - 2.0) << ' ' << 2.0 * 1.1 * 0.8 * decay * (decay - 1.0)
        << "  # row\n";
  };
  for (int k = 0; k <= 500; ++k) {
    row(3.0 + 0.01 * k);
    if (uneven && k == 0) row(3.005);
  }
  return path;
}

std::unique_ptr<PairStyle> make_table(bool uneven) {
  PairStyleParameters params;
  params.texts["file"] =
      write_morse_table(uneven ? "pbms_dpd_uneven.table" : "pbms_dpd_even.table", uneven);
  return PairStyleRegistry::create("table", params);
}

}  // namespace

TEST(DpdPairStyles, ForcesAreMinusTheEnergyGradient) {
  expect_forces_are_minus_energy_gradient(*make_morse(true), periodic_box(), 1);
  expect_forces_are_minus_energy_gradient(*make_morse(false), periodic_box(), 2);
  expect_forces_are_minus_energy_gradient(*make_lj_nm(), periodic_box(), 3);
  expect_forces_are_minus_energy_gradient(*make_sutton_chen(), periodic_box(), 4);
  expect_forces_are_minus_energy_gradient(*make_table(false), periodic_box(), 5);
  expect_forces_are_minus_energy_gradient(*make_table(true), periodic_box(), 6);
  expect_forces_are_minus_energy_gradient(*make_sutton_chen(0.7), periodic_box(), 7);
  // The knee: above every particle's density, and near the box's densities.
  expect_forces_are_minus_energy_gradient(*make_sutton_chen(0.5, 5.0, 0.2), periodic_box(), 8);
  expect_forces_are_minus_energy_gradient(*make_sutton_chen(0.7, 0.3, 2.0), periodic_box(), 9);
}

TEST(DpdPairStyles, VirialIsTheSumOfPairOuterProducts) {
  expect_virial_is_sum_of_pair_outer_products(*make_morse(true));
  expect_virial_is_sum_of_pair_outer_products(*make_lj_nm());
  expect_virial_is_sum_of_pair_outer_products(*make_sutton_chen());
  expect_virial_is_sum_of_pair_outer_products(*make_table(false));
}

TEST(DpdPairStyles, PeriodicVirialIsMinusTheStrainDerivativeOfEnergy) {
  expect_virial_is_minus_strain_derivative(*make_morse(true));
  expect_virial_is_minus_strain_derivative(*make_lj_nm());
  expect_virial_is_minus_strain_derivative(*make_sutton_chen());
  expect_virial_is_minus_strain_derivative(*make_sutton_chen(0.7));
  expect_virial_is_minus_strain_derivative(*make_sutton_chen(0.5, 5.0, 0.2));
  expect_virial_is_minus_strain_derivative(*make_table(false));
}

namespace {

// Energy and force on particle 0 of a dimer at distance r along x.
std::pair<double, double> dimer(PairStyle& style, double r) {
  OrthogonalBox box;
  box.hi = {50.0, 50.0, 50.0};
  box.periodic = {false, false, false};
  DpdParticles p;
  p.mass_per_type = {1.0};
  p.add(1, 0, {10.0 + r, 10.0, 10.0});
  p.add(2, 0, {10.0, 10.0, 10.0});
  HalfNeighbourList list(style.cutoff(), 0.0);
  list.build(p, box);
  const double energy = energy_forces(style, p, list).energy;
  return {energy, p.f[0][0]};
}

}  // namespace

// A concurrent run's rank holds owned particles, then ghosts (pairs with
// them are evaluated on both ranks, so each tallies half), then another
// program's points (evaluated on this rank only: tallied in full, and
// apart as partner_energy).
TEST(DpdPairStyles, APairWithAPartnerIsTalliedOnceAndApart) {
  Morse morse(0.8, 1.1, 5.11, kCutoff, true);
  OrthogonalBox box;
  box.hi = {50.0, 50.0, 50.0};
  box.periodic = {false, false, false};
  DpdParticles p;
  p.mass_per_type = {1.0, 1.0};
  p.add(1, 0, {10.0, 10.0, 10.0});        // owned
  p.add(2, 0, {14.5, 10.0, 10.0});        // a ghost
  p.add(3, 1, {10.0, 15.2, 10.0});        // a partner
  p.add(4, 1, {10.0, 10.0, 10.0 + 6.3});  // a partner
  HalfNeighbourList list(morse.cutoff(), 0.0);
  list.build(p, box, 1, 2);
  const double ghost = dimer(morse, 4.5).first;
  const double partners = dimer(morse, 5.2).first + dimer(morse, 6.3).first;
  const PairResult r = energy_forces(morse, p, list);
  EXPECT_NEAR(r.energy, 0.5 * ghost + partners, 1e-13);
  EXPECT_NEAR(r.partner_energy, partners, 1e-13);
  // The partners' virial, too, counts in full: yy and zz have no ghost term.
  const double fy = p.f[0][1], fz = p.f[0][2];
  EXPECT_NEAR(r.virial[1], -5.2 * fy, 1e-12);
  EXPECT_NEAR(r.virial[2], -6.3 * fz, 1e-12);
  // The energy alone, as a ledger kept every step asks for it.
  p.zero_forces();
  const PairResult energy_only = morse.compute(p, list, Tally::kEnergy);
  EXPECT_EQ(energy_only.energy, r.energy);
  EXPECT_EQ(energy_only.partner_energy, r.partner_energy);
  EXPECT_EQ(energy_only.virial, (std::array<double, 6>{}));
  // Without partners the same list tallies every pair with a ghost by half.
  list.build(p, box, 1);
  const PairResult all_ghosts = energy_forces(morse, p, list);
  EXPECT_NEAR(all_ghosts.energy, 0.5 * (ghost + partners), 1e-13);
  EXPECT_EQ(all_ghosts.partner_energy, 0.0);
}

TEST(DpdPairStyles, MorseMatchesTheLammpsDefinition) {
  Morse morse(0.8, 1.1, 5.11, kCutoff, false);
  EXPECT_NEAR(dimer(morse, 5.11).first, -0.8, 1e-15);
  EXPECT_NEAR(dimer(morse, 5.11).second, 0.0, 1e-14);
  const double r = 4.3;
  const double decay = std::exp(-1.1 * (r - 5.11));
  // The dimer's separation is (10 + r) − 10, exact to ~1e-15 Å.
  EXPECT_NEAR(dimer(morse, r).first, 0.8 * (decay * decay - 2.0 * decay), 1e-13);
  EXPECT_NEAR(dimer(morse, r).second, 2.0 * 1.1 * 0.8 * (decay * decay - decay), 1e-13);
}

TEST(DpdPairStyles, MorseShiftMakesTheEnergyZeroAtTheCutoff) {
  Morse unshifted(0.8, 1.1, 5.11, kCutoff, false);
  Morse shifted(0.8, 1.1, 5.11, kCutoff, true);
  const double just_inside = kCutoff * (1.0 - 1e-12);
  EXPECT_LT(dimer(unshifted, just_inside).first, -1e-3);
  EXPECT_NEAR(dimer(shifted, just_inside).first, 0.0, 1e-11);  // |dE/dr| · 1e-11 Å
  EXPECT_EQ(dimer(shifted, kCutoff * (1.0 + 1e-12)).first, 0.0);
  // The shift moves energies, not forces.
  EXPECT_DOUBLE_EQ(dimer(shifted, 6.0).second, dimer(unshifted, 6.0).second);
  EXPECT_NEAR(dimer(shifted, 6.0).first - dimer(unshifted, 6.0).first,
              -dimer(unshifted, just_inside).first, 1e-12);
}

TEST(DpdPairStyles, LjNmHasItsMinimumMinusE0AtR0) {
  LjNm lj(0.4, 5.11, 12.0, 6.0, kCutoff, false);
  EXPECT_NEAR(dimer(lj, 5.11).first, -0.4, 1e-15);
  EXPECT_NEAR(dimer(lj, 5.11).second, 0.0, 1e-14);
  const double s = 5.11 / 4.5;
  EXPECT_NEAR(dimer(lj, 4.5).first, 0.4 / 6.0 * (6.0 * std::pow(s, 12) - 12.0 * std::pow(s, 6)),
              1e-14);
}

TEST(DpdPairStyles, SuttonChenDimerEnergy) {
  SuttonChen sc(0.0124, 3.61, 9.0, 6.0, 39.4, kCutoff);
  const double r = 3.0;
  const double rho = std::pow(3.61 / r, 6.0);
  EXPECT_NEAR(dimer(sc, r).first, 0.0124 * (std::pow(3.61 / r, 9.0) - 39.4 * 2.0 * std::sqrt(rho)),
              1e-13);
  // Another embedding exponent: each atom of the dimer embeds rho^p.
  SuttonChen embedded(0.0124, 3.61, 9.0, 6.0, 39.4, kCutoff, 0.7);
  EXPECT_NEAR(dimer(embedded, r).first,
              0.0124 * (std::pow(3.61 / r, 9.0) - 39.4 * 2.0 * std::pow(rho, 0.7)), 1e-13);
  EXPECT_THROW(SuttonChen(0.0124, 3.61, 9.0, 6.0, 39.4, kCutoff, 1.0), pbms::Error);
}

// The knee's term, recomputed here: rho_c from the fcc shells within the
// cutoff (12 at a/sqrt2, 6 at a, 24 at a sqrt(3/2), 12 at a sqrt2, 24 at
// a sqrt(5/2), 8 at a sqrt3, ...), and the dimer's density far below it.
TEST(DpdPairStyles, SuttonChenKneeFlattensTheEmbeddingBelowTheCrystalDensity) {
  const double a = 3.61, m = 6.0, knee = 0.9, flattening = 0.4;
  double rho_c = 0.0;
  const std::pair<int, double> shells[] = {{12, 0.5}, {6, 1.0},  {24, 1.5}, {12, 2.0},
                                           {24, 2.5}, {8, 3.0},  {48, 3.5}, {6, 4.0},
                                           {36, 4.5}, {24, 5.0}, {24, 5.5}, {24, 6.0}};
  for (const auto& [count, s2] : shells) {
    if (s2 * a * a < kCutoff * kCutoff) rho_c += count * std::pow(s2, -0.5 * m);
  }
  SuttonChen sc(0.0124, a, 9.0, m, 39.4, kCutoff, 0.5, knee, flattening);
  ASSERT_LT(kCutoff * kCutoff, 6.0 * a * a);  // the shells above cover the cutoff
  EXPECT_NEAR(sc.crystal_density(), rho_c, 1e-12 * rho_c);
  const double r = 3.0;
  const double rho = std::pow(a / r, m);
  ASSERT_LT(rho, knee * rho_c);
  const double below = knee - rho / rho_c;
  const double embedded = std::sqrt(rho) + flattening * std::sqrt(rho_c) * below * below * below;
  EXPECT_NEAR(dimer(sc, r).first, 0.0124 * (std::pow(a / r, 9.0) - 39.4 * 2.0 * embedded), 1e-12);
  // No flattening is the plain form, to the bit.
  SuttonChen plain(0.0124, a, 9.0, m, 39.4, kCutoff);
  SuttonChen unflattened(0.0124, a, 9.0, m, 39.4, kCutoff, 0.5, knee, 0.0);
  EXPECT_EQ(dimer(plain, r).first, dimer(unflattened, r).first);
  EXPECT_EQ(dimer(plain, r).second, dimer(unflattened, r).second);
  EXPECT_THROW(SuttonChen(0.0124, a, 9.0, m, 39.4, kCutoff, 0.5, 0.0, 0.1), pbms::Error);
  EXPECT_THROW(SuttonChen(0.0124, a, 9.0, m, 39.4, kCutoff, 0.5, 1.0, -0.1), pbms::Error);
}

// A concurrent run's MPM points pair with the DPD particles but are no list
// rows, so a many-body style gives each the mean density of the particles
// it pairs with. Half of a perfect periodic crystal owned and the other half
// partners is then the whole crystal: every owned particle has the
// crystal's density (the lattice sum, recomputed here) and, by the
// lattice's symmetry, no net force, the planes at the interface included.
TEST(DpdPairStyles, SuttonChenPartnersStandForCrystalSites) {
  const double a = 7.23, n = 9.0, m = 6.0, cutoff = 11.8;
  SuttonChen sc(0.099056, a, n, m, 39.432, cutoff);
  FccCrystal crystal = fcc_crystal(4, 4, 4, a, 508.37);
  DpdParticles p;
  p.mass_per_type = {508.37, 508.37};
  const double half = 0.5 * crystal.box.length(0) - 0.1;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < crystal.particles.size(); ++i) {
      const Vec3& x = crystal.particles.x[i];
      if ((x[0] < half) == (pass == 0)) p.add(crystal.particles.id[i], pass, x);
    }
  }
  const std::size_t owned = crystal.particles.size() / 2;
  HalfNeighbourList list(cutoff, kSkin);
  list.build(p, crystal.box, owned, owned);
  energy_forces(sc, p, list);

  double rho0 = 0.0;  // the 12, 6, 24, 12 and 24 sites of the first five shells
  const double shells[5][2] = {{12, 0.5}, {6, 1.0}, {24, 1.5}, {12, 2.0}, {24, 2.5}};
  for (const auto& [count, r2_over_a2] : shells) {
    if (r2_over_a2 * a * a < cutoff * cutoff) rho0 += count * std::pow(r2_over_a2, -0.5 * m);
  }
  const double scale = 0.099056 * n / a;  // a pair force at r = a, eV/Å
  for (std::size_t i = 0; i < owned; ++i) {
    EXPECT_NEAR(sc.density()[i], rho0, 1e-12 * rho0) << "particle " << i;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.f[i][k], 0.0, 1e-12 * scale) << "particle " << i;
  }
}

TEST(DpdPairStyles, TableReproducesItsRowsAndInterpolatesSmoothly) {
  PairTable table(read_pair_table(write_morse_table("pbms_dpd_rows.table", true)), kCutoff);
  double energy = 0.0, force = 0.0;
  for (double r : {3.0, 3.005, 3.01, 4.2, 5.11, 7.99}) {
    const double decay = std::exp(-1.1 * (r - 5.11));
    table.interpolate(r, energy, force);
    EXPECT_NEAR(energy, 0.8 * decay * (decay - 2.0), 1e-12) << r;
    EXPECT_NEAR(force, 2.0 * 1.1 * 0.8 * decay * (decay - 1.0), 1e-12) << r;
  }
  // Between rows 0.01 Å apart: Hermite error ~ h^4 U'''' / 384 in energy, O(h^3) in force.
  for (double r : {3.5033, 5.1149, 6.7771}) {
    const double decay = std::exp(-1.1 * (r - 5.11));
    table.interpolate(r, energy, force);
    const double exact_energy = 0.8 * decay * (decay - 2.0);
    const double exact_force = 2.0 * 1.1 * 0.8 * decay * (decay - 1.0);
    EXPECT_NEAR(energy, exact_energy, 1e-8 * std::abs(exact_energy)) << r;
    EXPECT_NEAR(force, exact_force, 1e-6 * std::abs(exact_force)) << r;
  }
  EXPECT_THROW(table.interpolate(2.99, energy, force), pbms::Error);
}

TEST(DpdPairStyles, TableFileErrorsNameTheLine) {
  const auto path = (std::filesystem::temp_directory_path() / "pbms_dpd_bad.table").string();
  std::ofstream(path) << "# header\n1.0 2.0 3.0\n1.5 2.0\n";
  try {
    read_pair_table(path);
    FAIL() << "a two-column row was accepted";
  } catch (const pbms::Error& e) {
    EXPECT_NE(std::string(e.what()).find(":3:"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "1.0 2.0 3.0\n0.9 2.0 3.0\n";
  EXPECT_THROW(read_pair_table(path), pbms::Error);
  EXPECT_THROW(read_pair_table(path + ".missing"), pbms::Error);
}

TEST(DpdPairStyleRegistry, CreatesEveryBuiltInStyleByName) {
  EXPECT_EQ(PairStyleRegistry::names(),
            (std::vector<std::string>{"lj_nm", "morse", "sutton_chen", "table"}));
  PairStyleParameters morse;
  morse.numbers = {{"d0", 1.0}, {"alpha", 1.0}, {"r0", 5.11}, {"cutoff", 10.0}, {"shift", 1.0}};
  EXPECT_EQ(PairStyleRegistry::create("morse", morse)->name(), "morse");
  PairStyleParameters lj;
  lj.numbers = {{"e0", 0.4}, {"r0", 5.11}, {"n", 12.0}, {"m", 6.0}, {"cutoff", 10.0}};
  EXPECT_EQ(PairStyleRegistry::create("lj_nm", lj)->cutoff(), 10.0);
  PairStyleParameters sc;
  sc.numbers = {{"epsilon", 0.0124}, {"a", 3.61}, {"n", 9.0},
                {"m", 6.0},          {"c", 39.4}, {"cutoff", 10.0}};
  EXPECT_EQ(PairStyleRegistry::create("sutton_chen", sc)->name(), "sutton_chen");
  EXPECT_EQ(make_table(false)->cutoff(), 8.0);  // the last row
}

TEST(DpdPairStyleRegistry, RefusesUnknownStylesAndBadParameters) {
  try {
    PairStyleRegistry::create("morse/opt", {});
    FAIL();
  } catch (const pbms::Error& e) {
    EXPECT_NE(std::string(e.what()).find("sutton_chen"), std::string::npos) << e.what();
  }
  PairStyleParameters morse;
  morse.numbers = {{"d0", 1.0}, {"alpha", 1.0}, {"r0", 5.11}, {"cutof", 10.0}};
  EXPECT_THROW(PairStyleRegistry::create("morse", morse), pbms::Error);  // missing cutoff
  morse.numbers["cutoff"] = 10.0;
  EXPECT_THROW(PairStyleRegistry::create("morse", morse), pbms::Error);  // unknown "cutof"
  morse.numbers.erase("cutof");
  morse.numbers["shift"] = 0.5;
  EXPECT_THROW(PairStyleRegistry::create("morse", morse), pbms::Error);
  morse.numbers["shift"] = 1.0;
  morse.numbers["alpha"] = -1.0;
  EXPECT_THROW(PairStyleRegistry::create("morse", morse), pbms::Error);
  PairStyleParameters lj;
  lj.numbers = {{"e0", 0.4}, {"r0", 5.11}, {"n", 6.0}, {"m", 12.0}, {"cutoff", 10.0}};
  EXPECT_THROW(PairStyleRegistry::create("lj_nm", lj), pbms::Error);  // n < m
  EXPECT_THROW(PairStyleRegistry::add("morse", &Morse::create, Morse::params(), ""), pbms::Error);
}
