// The DPD/DPDE integrators on the mesoparticle copper crystal (fitted Morse,
// docs/dpd-morse-fit.md): NVE conservation, the DPD thermostat's temperature
// and velocity distribution, DPDE energy conservation, Shardlow against
// velocity Verlet, Berendsen equilibration.
//
// DpdIntegratorsFullSize and DISABLED_DpdIntegratorsLong run the sizes of
// the specification (4,000 particles, 10,000 steps or 20 ps). The first
// takes ~10 s and runs with the unit tests; the long ones (~6 min) run as
// the ctest `dpd_integrators_full_size` with the `validation` label. The
// DpdIntegrators ones check the same physics on smaller crystals in seconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "cu_cg_morse.hpp"
#include "integrators/berendsen_thermostat.hpp"
#include "integrators/dpd_integrator.hpp"
#include "kernels/fcc_crystal.hpp"
#include "kernels/kinetic_sums.hpp"
#include "kernels/maxwell_boltzmann_velocities.hpp"
#include "pbms/analysis/block_average.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

using namespace pbms::dpd;
using pbms::units::kBoltzmann;
using pbms::units::kMvv2e;

namespace {

constexpr double kLattice = 7.23;  // Å
constexpr double kMass = 508.37;   // g/mol
constexpr double kRoomTemperature = 298.0;
// 8 atoms, 3 × 8 − 3 internal vibrational modes, each k_B classically.
constexpr double kMesoparticleHeatCapacity = 21.0 * kBoltzmann;  // eV/K
// Strong enough that the thermostat relaxes the crystal in a few ps (the
// seed's 0.2 g/mol/ps takes ~1 ns, which is why it equilibrates with Berendsen).
constexpr double kTestGamma = 500.0;  // g/mol/ps

// The crystal at rest on its lattice with Maxwell–Boltzmann velocities at
// twice the target: equipartition with the harmonic potential energy then
// brings the kinetic temperature close to the target within a phonon period.
FccCrystal thermal_crystal(int cells, double kinetic_temperature) {
  FccCrystal crystal = fcc_crystal(cells, cells, cells, kLattice, kMass);
  assign_maxwell_boltzmann_velocities(crystal.particles, kinetic_temperature, 2024);
  return crystal;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Kolmogorov's limiting distribution Q(λ) = 2 Σ (−1)^{k−1} exp(−2 k² λ²) of
// √n D, with the finite-n correction λ = (√n + 0.12 + 0.11/√n) D of
// Stephens (1970) as in Numerical Recipes §14.3.
double kolmogorov_smirnov_p_value(double statistic, std::size_t n) {
  const double root_n = std::sqrt(static_cast<double>(n));
  const double lambda = (root_n + 0.12 + 0.11 / root_n) * statistic;
  if (lambda < 0.2) return 1.0;  // the series converges slowly there, and Q ≈ 1
  double sum = 0.0;
  double sign = 1.0;
  for (int k = 1; k <= 100; ++k) {
    const double term = sign * std::exp(-2.0 * k * k * lambda * lambda);
    sum += term;
    if (std::abs(term) < 1e-12 * std::abs(sum)) break;
    sign = -sign;
  }
  return std::clamp(2.0 * sum, 0.0, 1.0);
}

// sup |F_n(z) − Φ(z)| of a sample against the unit normal.
double kolmogorov_smirnov_statistic(std::vector<double> sample) {
  std::sort(sample.begin(), sample.end());
  const double n = static_cast<double>(sample.size());
  double d = 0.0;
  for (std::size_t k = 0; k < sample.size(); ++k) {
    const double cdf = 0.5 * std::erfc(-sample[k] / std::numbers::sqrt2);
    d = std::max({d, (k + 1) / n - cdf, cdf - k / n});
  }
  return d;
}

// Velocity components scaled by the Maxwell–Boltzmann width at temperature.
std::vector<double> reduced_velocity_components(const DpdParticles& particles, double temperature) {
  std::vector<double> z;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double width = std::sqrt(kBoltzmann * temperature / (particles.mass(i) * kMvv2e));
    for (int a = 0; a < 3; ++a) z.push_back(particles.v[i][a] / width);
  }
  return z;
}

// Conservation figures of a run. Velocity Verlet conserves a shadow energy,
// so E itself fluctuates by O((ω Δt)²) of the thermal energy (ω Δt ≈ 0.3
// for the fastest phonons here) without drifting: the drift is the slope
// of a straight line through E(t), times the run's duration.
struct Conservation {
  double drift_of_total;    // |slope| t_run / |E0|
  double drift_of_thermal;  // |slope| t_run / thermal energy at start: what an error would heat
  double fluctuation;       // max |E − E0| / thermal energy at start
  double momentum;          // max |Σ m v| / Σ m |v|
};

Conservation conservation(const std::vector<double>& time, const std::vector<double>& energy,
                          double e0, double thermal0, double momentum) {
  const double drift =
      std::abs(pbms::analysis::fit_line(time, energy).slope) * (time.back() - time.front());
  double fluctuation = 0.0;
  for (const double e : energy) fluctuation = std::max(fluctuation, std::abs(e - e0));
  return {drift / std::abs(e0), drift / thermal0, fluctuation / thermal0, momentum};
}

Conservation run_nve(int cells, int steps, double dt) {
  FccCrystal crystal = thermal_crystal(cells, 2.0 * kRoomTemperature);
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  DpdIntegratorSettings settings;
  settings.dt = dt;
  DpdIntegrator integrator(crystal.particles, crystal.box, *morse, settings);
  const double k0 = kinetic_energy(crystal.particles);
  const double e0 = k0 + integrator.potential().energy;
  std::vector<double> time, energy;
  double momentum = 0.0;
  for (int s = 1; s <= steps; ++s) {
    const bool sample = s % 20 == 0;
    const PairResult pair = integrator.step(sample ? Tally::kEnergyAndVirial : Tally::kForcesOnly);
    if (!sample) continue;
    time.push_back(s * dt);
    energy.push_back(kinetic_energy(crystal.particles) + pair.energy);
    const Vec3 p = total_momentum(crystal.particles);
    momentum = std::max(momentum, std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) /
                                      momentum_magnitude_sum(crystal.particles));
  }
  const Conservation c = conservation(time, energy, e0, k0, momentum);
  std::printf(
      "NVE %zu particles, %d steps of %.3f ps: drift/|E0| = %.2e, drift/K0 = %.2e, "
      "max |E - E0|/K0 = %.2e, max |P|/sum m|v| = %.2e\n",
      crystal.particles.size(), steps, dt, c.drift_of_total, c.drift_of_thermal, c.fluctuation,
      c.momentum);
  return c;
}

struct ThermostatRun {
  double mean_temperature;
  double standard_error;
  double ks_p_value;
};

// Kinetic temperature under a DPD scheme at 298 K, averaged every step over
// production_ps after equilibration_ps, and the KS p-value of the final
// velocity components against Maxwell–Boltzmann at 298 K. The crystal starts
// at 298 K kinetic, so the thermostat must supply the potential half of the
// heat (it would sit near 149 K without it).
ThermostatRun run_thermostat(DpdScheme scheme, int cells, double equilibration_ps,
                             double production_ps, std::uint64_t seed) {
  FccCrystal crystal = thermal_crystal(cells, kRoomTemperature);
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  DpdIntegratorSettings settings;
  settings.scheme = scheme;
  settings.dt = 0.01;
  settings.friction = {kTestGamma, 10.0, kRoomTemperature, seed};
  DpdIntegrator integrator(crystal.particles, crystal.box, *morse, settings);
  const int equilibration = static_cast<int>(std::lround(equilibration_ps / settings.dt));
  const int production = static_cast<int>(std::lround(production_ps / settings.dt));
  for (int s = 0; s < equilibration; ++s) integrator.step();
  std::vector<double> temperature;
  for (int s = 0; s < production; ++s) {
    integrator.step();
    temperature.push_back(kinetic_temperature(crystal.particles));
  }
  const std::vector<double> z = reduced_velocity_components(crystal.particles, kRoomTemperature);
  // Blocks of 5 ps: the temperature of this damped crystal stays correlated
  // over a few ps (in a 400-ps run the block error levels off from 4-ps
  // blocks on; 2-ps blocks gave 20 % less, and ten of them over 20 ps about
  // 40 % less than the scatter between seeds).
  const int blocks = std::max(2, static_cast<int>(production_ps / 5.0));
  ThermostatRun run{pbms::analysis::mean(temperature),
                    pbms::analysis::block_average(temperature, blocks).error,
                    kolmogorov_smirnov_p_value(kolmogorov_smirnov_statistic(z), z.size())};
  std::printf("%s, %zu particles, %.0f + %.0f ps: <T> = %.2f +- %.2f K, KS p = %.3f\n",
              scheme == DpdScheme::kShardlow ? "Shardlow" : "velocity Verlet",
              crystal.particles.size(), equilibration_ps, production_ps, run.mean_temperature,
              run.standard_error, run.ks_p_value);
  return run;
}

// DPDE with γ > 0 from a crystal whose internal degrees of freedom are
// hotter than its mesoparticle motion, so that heat flows between them
// during the run; E = K + U + Σu.
Conservation run_dpde(int cells, int steps, double dt) {
  FccCrystal crystal = thermal_crystal(cells, 2.0 * kRoomTemperature);
  crystal.particles.internal_energy.assign(crystal.particles.size(),
                                           kMesoparticleHeatCapacity * 1.5 * kRoomTemperature);
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  DpdIntegratorSettings settings;
  settings.scheme = DpdScheme::kShardlowDpde;
  settings.dt = dt;
  settings.friction = {kTestGamma, 10.0, 0.0, 77};
  settings.heat_capacity = kMesoparticleHeatCapacity;
  DpdIntegrator integrator(crystal.particles, crystal.box, *morse, settings);
  const double u0 = internal_energy_sum(crystal.particles);
  const double thermal0 = kinetic_energy(crystal.particles) + u0;
  const double e0 = thermal0 + integrator.potential().energy;
  std::vector<double> time, energy;
  double momentum = 0.0;
  for (int s = 1; s <= steps; ++s) {
    const bool sample = s % 20 == 0;
    const PairResult pair = integrator.step(sample ? Tally::kEnergyAndVirial : Tally::kForcesOnly);
    if (!sample) continue;
    time.push_back(s * dt);
    energy.push_back(kinetic_energy(crystal.particles) + pair.energy +
                     internal_energy_sum(crystal.particles));
    const Vec3 p = total_momentum(crystal.particles);
    momentum = std::max(momentum, std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) /
                                      momentum_magnitude_sum(crystal.particles));
  }
  const Conservation c = conservation(time, energy, e0, thermal0, momentum);
  std::printf(
      "DPDE %zu particles, gamma %.0f g/mol/ps, %d steps of %.4f ps: drift/|E0| = %.2e, "
      "drift/(K0 + U_int0) = %.2e, max |E - E0|/(K0 + U_int0) = %.2e, "
      "max |P|/sum m|v| = %.1e; sum u %.1f -> %.1f eV, T %.1f K\n",
      crystal.particles.size(), kTestGamma, steps, dt, c.drift_of_total, c.drift_of_thermal,
      c.fluctuation, c.momentum, u0, internal_energy_sum(crystal.particles),
      kinetic_temperature(crystal.particles));
  return c;
}

}  // namespace

TEST(DpdIntegrators, KolmogorovSmirnovPValueMatchesTabulatedCriticalValues) {
  // Asymptotic critical values √n D: 1.358 at 5 %, 1.628 at 1 %.
  const std::size_t n = 1'000'000;
  EXPECT_NEAR(kolmogorov_smirnov_p_value(1.358 / std::sqrt(1e6), n), 0.05, 1e-3);
  EXPECT_NEAR(kolmogorov_smirnov_p_value(1.628 / std::sqrt(1e6), n), 0.01, 2e-4);
  std::vector<double> quantiles;
  for (int k = 0; k < 2000; ++k) {
    // Normal quantiles by bisection on erfc, a deterministic "perfect" sample.
    const double target = (k + 0.5) / 2000.0;
    double lo = -10.0, hi = 10.0;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      (0.5 * std::erfc(-mid / std::numbers::sqrt2) < target ? lo : hi) = mid;
    }
    quantiles.push_back(0.5 * (lo + hi));
  }
  EXPECT_GT(kolmogorov_smirnov_p_value(kolmogorov_smirnov_statistic(quantiles), 2000), 0.99);
  // The same sample shifted by 0.2 standard deviations fails clearly.
  for (double& q : quantiles) q += 0.2;
  EXPECT_LT(kolmogorov_smirnov_p_value(kolmogorov_smirnov_statistic(quantiles), 2000), 1e-6);
}

TEST(DpdIntegrators, NveConservesEnergyAndMomentum) {
  const auto start = std::chrono::steady_clock::now();
  const Conservation nve = run_nve(4, 2000, 0.01);  // 256 particles, 20 ps
  EXPECT_LT(nve.drift_of_total, 1e-5);
  EXPECT_LT(nve.drift_of_thermal, 1e-3);
  EXPECT_LT(nve.momentum, 1e-12);
  std::printf("  (%.1f s)\n", seconds_since(start));
}

TEST(DpdIntegratorsFullSize, NveConservesEnergyAndMomentumOver10000Steps) {
  const auto start = std::chrono::steady_clock::now();
  const Conservation nve = run_nve(10, 10000, 0.01);  // 4,000 particles, 100 ps
  EXPECT_LT(nve.drift_of_total, 1e-4);
  EXPECT_LT(nve.drift_of_thermal, 1e-3);
  EXPECT_LT(nve.momentum, 1e-10);
  std::printf("  (%.1f s)\n", seconds_since(start));
}

TEST(DpdIntegrators, DpdeConservesTotalEnergyForThreeTimeSteps) {
  const auto start = std::chrono::steady_clock::now();
  for (const double dt : {0.005, 0.01, 0.02}) {
    const Conservation dpde = run_dpde(4, static_cast<int>(std::lround(10.0 / dt)), dt);
    EXPECT_LT(dpde.drift_of_total, 1e-4);
    EXPECT_LT(dpde.drift_of_thermal, 1e-2);
    EXPECT_LT(dpde.momentum, 1e-12);
  }
  std::printf("  (%.1f s)\n", seconds_since(start));
}

TEST(DISABLED_DpdIntegratorsLong, DpdeConservesTotalEnergyOver10000Steps) {
  const auto start = std::chrono::steady_clock::now();
  for (const double dt : {0.005, 0.01, 0.02}) {
    const Conservation dpde = run_dpde(10, 10000, dt);
    EXPECT_LT(dpde.drift_of_total, 1e-3);
    EXPECT_LT(dpde.drift_of_thermal, 1e-2);
    EXPECT_LT(dpde.momentum, 1e-10);
  }
  std::printf("  (%.1f s)\n", seconds_since(start));
}

TEST(DpdIntegrators, DpdThermostatHeatsTheCrystalTo298KWithMaxwellBoltzmannVelocities) {
  const auto start = std::chrono::steady_clock::now();
  // 500 particles: the thermal energy fluctuates by ~sqrt(1 / 3N) = 2.6 % and
  // decorrelates over the ~2 ps relaxation time, so a 20 ps mean scatters by
  // ~1 % between seeds (295.0 to 304.0 K seen over five). 3 % is three of
  // those; the 1 % criterion is checked at 4,000 particles (FullSize).
  const ThermostatRun run = run_thermostat(DpdScheme::kVelocityVerlet, 5, 10.0, 20.0, 3);
  EXPECT_NEAR(run.mean_temperature, kRoomTemperature, 0.03 * kRoomTemperature);
  EXPECT_GT(run.ks_p_value, 0.01);
  std::printf("  (%.1f s)\n", seconds_since(start));
}

TEST(DpdIntegrators, ShardlowAndVelocityVerletAgreeOnTemperature) {
  const auto start = std::chrono::steady_clock::now();
  const ThermostatRun verlet = run_thermostat(DpdScheme::kVelocityVerlet, 5, 10.0, 40.0, 11);
  const ThermostatRun shardlow = run_thermostat(DpdScheme::kShardlow, 5, 10.0, 40.0, 12);
  const double combined = std::hypot(verlet.standard_error, shardlow.standard_error);
  EXPECT_LT(std::abs(verlet.mean_temperature - shardlow.mean_temperature),
            std::max(3.0 * combined, 0.01 * kRoomTemperature));
  EXPECT_NEAR(shardlow.mean_temperature, kRoomTemperature, 0.03 * kRoomTemperature);
  EXPECT_GT(shardlow.ks_p_value, 0.01);
  std::printf("  (%.1f s)\n", seconds_since(start));
}

TEST(DISABLED_DpdIntegratorsLong, DpdThermostatHolds298KAndShardlowAgreesWithVelocityVerlet) {
  const auto start = std::chrono::steady_clock::now();
  // 4,000 particles, 10 ps to heat from the 149 K of equipartition (the
  // relaxation time at γ = 500 g/mol/ps is ~2 ps), then 20 ps averaged.
  const ThermostatRun verlet = run_thermostat(DpdScheme::kVelocityVerlet, 10, 10.0, 20.0, 21);
  EXPECT_NEAR(verlet.mean_temperature, kRoomTemperature, 0.01 * kRoomTemperature);
  EXPECT_GT(verlet.ks_p_value, 0.01);
  const ThermostatRun shardlow = run_thermostat(DpdScheme::kShardlow, 10, 10.0, 20.0, 22);
  EXPECT_NEAR(shardlow.mean_temperature, kRoomTemperature, 0.01 * kRoomTemperature);
  EXPECT_GT(shardlow.ks_p_value, 0.01);
  const double combined = std::hypot(verlet.standard_error, shardlow.standard_error);
  EXPECT_LT(std::abs(verlet.mean_temperature - shardlow.mean_temperature),
            std::max(3.0 * combined, 0.005 * kRoomTemperature));
  std::printf("  (%.1f s)\n", seconds_since(start));
}

TEST(DpdIntegrators, BerendsenBringsTheCrystalTo298K) {
  const auto start = std::chrono::steady_clock::now();
  FccCrystal crystal = thermal_crystal(4, kRoomTemperature);
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  DpdIntegratorSettings settings;  // NVE + Berendsen, as the seed equilibrates
  DpdIntegrator integrator(crystal.particles, crystal.box, *morse, settings);
  const double tau = 0.5;  // ps
  std::vector<double> temperature;
  for (int s = 0; s < 2000; ++s) {
    integrator.step();
    berendsen_rescale(crystal.particles, kRoomTemperature, settings.dt, tau);
    if (s >= 1000) temperature.push_back(kinetic_temperature(crystal.particles));
  }
  const double mean = pbms::analysis::mean(temperature);
  std::printf("Berendsen, 256 particles, tau %.1f ps: <T> over 10-20 ps = %.2f K  (%.1f s)\n", tau,
              mean, seconds_since(start));
  // Weak coupling suppresses the fluctuations, so the mean is tight.
  EXPECT_NEAR(mean, kRoomTemperature, 0.01 * kRoomTemperature);
  const Vec3 p = total_momentum(crystal.particles);
  EXPECT_LT(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]),
            1e-12 * momentum_magnitude_sum(crystal.particles));
}

TEST(DpdIntegrators, RefusesMeaninglessSettings) {
  FccCrystal crystal = thermal_crystal(4, kRoomTemperature);
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  DpdIntegratorSettings settings;
  settings.dt = 0.0;
  EXPECT_THROW(DpdIntegrator(crystal.particles, crystal.box, *morse, settings), pbms::Error);
  settings.dt = 0.01;
  settings.scheme = DpdScheme::kShardlowDpde;
  settings.friction = {1.0, 10.0, 0.0, 1};
  EXPECT_THROW(DpdIntegrator(crystal.particles, crystal.box, *morse, settings), pbms::Error);
  settings.heat_capacity = kMesoparticleHeatCapacity;  // but every u_i is still zero
  DpdIntegrator dpde(crystal.particles, crystal.box, *morse, settings);
  EXPECT_THROW(dpde.step(), pbms::Error);
}
