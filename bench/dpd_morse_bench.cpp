// The PBMS half of bench/dpd_morse.sh: step throughput of the DPD engine on
// one core for the copper mesoparticle crystal, and what the DPD thermostat
// adds to it.
//
// Setup: 32,000 mesoparticles (periodic fcc, 20 × 20 × 20 cells,
// a = 7.23 Å, 508.37 g/mol), the Morse fit of docs/dpd-morse-fit.md as
// configs/potentials/cu_cg_morse.yaml holds it (shift yes, r_c = 10 Å),
// skin 1 Å, dt = 0.01 ps, 1,000 steps, velocities Maxwell–Boltzmann at
// 298 K. Runs
//   - NVE (DpdScheme::kNve): the script's BENCH dpd_particle_steps_per_s,
//     set against lmp pair_style morse and morse/opt on the same state
//     (target: PBMS ≥ 1.2 × the faster LAMMPS run);
//   - full DPD (kVelocityVerlet, γ = 0.2 g/mol/ps, 298 K, DPD cutoff
//     10 Å), with θ uniform as stages draw it by default ("dpd" or
//     "dpd_uniform") or Gaussian ("dpd_gaussian");
//   - "thermostat": NVE and both DPD runs interleaved in one process
//     (thermostat_cost below), for BENCH dpd_thermostat_cost = full DPD over
//     NVE (target ≤ 1.5) and dpd_thermostat_cost_gaussian.
//
// Usage: dpd_morse_bench WORK_DIR writes WORK_DIR/data.lmp (positions and
// the very velocities PBMS starts from, so that lmp runs the same
// trajectory) and WORK_DIR/in.morse (pair style chosen by -var pair);
// dpd_morse_bench WORK_DIR nve|dpd times one run and prints its processor
// time and energies. One run per call lets the script interleave PBMS and
// lmp runs, so that a slow spell of a shared machine hits both alike.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "cu_cg_morse.hpp"
#include "integrators/dpd_integrator.hpp"
#include "kernels/fcc_crystal.hpp"
#include "kernels/kinetic_sums.hpp"
#include "kernels/maxwell_boltzmann_velocities.hpp"

using namespace pbms::dpd;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kDpdCutoff = 10.0;  // Å, of the thermostat's pair forces
constexpr double kSkin = 1.0;        // Å
constexpr double kLattice = 7.23;    // Å
constexpr double kMass = 508.37;     // g/mol
constexpr int kCells = 20;
constexpr double kDt = 0.01;  // ps
constexpr int kSteps = 1000;
constexpr double kTemperature = 298.0;  // K
constexpr double kGamma = 0.2;          // g/mol/ps
constexpr std::uint64_t kSeed = 4928;

// Processor time of this (single-threaded) process, s. The rates use it
// rather than wall time so that other work on a shared machine, which takes
// whole time slices, does not decide the ratios; on an idle machine the two
// agree. The script reads lmp's Loop time times its "% CPU use" for the same.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct RunResult {
  double seconds = 0.0;            // processor time of the steps
  double wall_seconds = 0.0;       // for the record
  double initial_potential = 0.0;  // eV
  double initial_kinetic = 0.0;    // eV
  double final_potential = 0.0;    // eV
  double final_kinetic = 0.0;      // eV
  long list_builds = 0;
};

RunResult run(const FccCrystal& start, DpdScheme scheme, PairNoiseDistribution noise) {
  FccCrystal crystal = start;
  const std::unique_ptr<PairStyle> morse = cu_cg_morse();
  DpdIntegratorSettings settings;
  settings.scheme = scheme;
  settings.dt = kDt;
  settings.skin = kSkin;
  settings.friction = {kGamma, kDpdCutoff, kTemperature, kSeed, noise};
  DpdIntegrator integrator(crystal.particles, crystal.box, *morse, settings);
  RunResult result;
  result.initial_potential = integrator.potential().energy;
  result.initial_kinetic = kinetic_energy(crystal.particles);
  const auto t0 = Clock::now();
  const double c0 = cpu_seconds();
  for (int n = 0; n < kSteps; ++n) integrator.step();
  result.seconds = cpu_seconds() - c0;
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  result.final_potential = integrator.potential().energy;
  result.final_kinetic = kinetic_energy(crystal.particles);
  result.list_builds = integrator.neighbour_list().build_count();
  return result;
}

// The thermostat's cost as the issue defines it, full DPD over conservative
// only, measured so that a slow spell of a shared machine cannot decide it:
// NVE, DPD with the default (uniform) θ and DPD with Gaussian θ advance in
// turn by windows of kWindowSteps from the same start, kSteps each in all;
// a window's ratio is the DPD window over the NVE window just before it,
// and the cost is the median over the rounds. Whole 1,000-step runs, as the
// throughput figures use, scatter by ±0.1 in this ratio on the development
// VM; the interleaved median by about ±0.03.
struct ThermostatCost {
  double uniform = 0.0;   // median window ratio, default θ
  double gaussian = 0.0;  // median window ratio, Gaussian θ
  double nve_seconds = 0.0, uniform_seconds = 0.0, gaussian_seconds = 0.0;  // totals
};

ThermostatCost thermostat_cost(const FccCrystal& start) {
  constexpr int kWindowSteps = 25;
  constexpr int kRounds = kSteps / kWindowSteps;
  struct Run {
    FccCrystal crystal;
    std::unique_ptr<PairStyle> morse = cu_cg_morse();
    std::unique_ptr<DpdIntegrator> integrator;
    std::vector<double> window;
    double total = 0.0;
  };
  Run runs[3];
  const DpdScheme schemes[3] = {DpdScheme::kNve, DpdScheme::kVelocityVerlet,
                                DpdScheme::kVelocityVerlet};
  const PairNoiseDistribution noises[3] = {DpdPairFriction{}.noise, DpdPairFriction{}.noise,
                                           PairNoiseDistribution::kGaussian};
  for (int k = 0; k < 3; ++k) {
    runs[k].crystal = start;
    DpdIntegratorSettings settings;
    settings.scheme = schemes[k];
    settings.dt = kDt;
    settings.skin = kSkin;
    settings.friction = {kGamma, kDpdCutoff, kTemperature, kSeed, noises[k]};
    runs[k].integrator = std::make_unique<DpdIntegrator>(
        runs[k].crystal.particles, runs[k].crystal.box, *runs[k].morse, settings);
  }
  for (int round = 0; round < kRounds; ++round) {
    for (Run& r : runs) {
      const double c0 = cpu_seconds();
      for (int n = 0; n < kWindowSteps; ++n) r.integrator->step();
      r.window.push_back(cpu_seconds() - c0);
      r.total += r.window.back();
    }
  }
  auto median_ratio = [&](const Run& dpd) {
    std::vector<double> ratio(kRounds);
    for (int w = 0; w < kRounds; ++w) ratio[w] = dpd.window[w] / runs[0].window[w];
    std::nth_element(ratio.begin(), ratio.begin() + kRounds / 2, ratio.end());
    return ratio[kRounds / 2];
  };
  return {median_ratio(runs[1]), median_ratio(runs[2]), runs[0].total, runs[1].total,
          runs[2].total};
}

bool write_lammps_files(const std::string& dir, const FccCrystal& crystal,
                        const CuCgMorseParameters& morse) {
  const DpdParticles& p = crystal.particles;
  std::FILE* data = std::fopen((dir + "/data.lmp").c_str(), "w");
  if (data == nullptr) return false;
  std::fprintf(data, "PBMS dpd_morse bench: fcc mesoparticle copper at 298 K\n\n");
  std::fprintf(data, "%zu atoms\n1 atom types\n\n", p.size());
  const char* axis[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    std::fprintf(data, "%.17g %.17g %slo %shi\n", crystal.box.lo[a], crystal.box.hi[a], axis[a],
                 axis[a]);
  }
  std::fprintf(data, "\nMasses\n\n1 %.17g\n\nAtoms # atomic\n\n", kMass);
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::fprintf(data, "%lld 1 %.17g %.17g %.17g\n", static_cast<long long>(p.id[i]), p.x[i][0],
                 p.x[i][1], p.x[i][2]);
  }
  std::fprintf(data, "\nVelocities\n\n");
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::fprintf(data, "%lld %.17g %.17g %.17g\n", static_cast<long long>(p.id[i]), p.v[i][0],
                 p.v[i][1], p.v[i][2]);
  }
  std::fclose(data);

  std::FILE* in = std::fopen((dir + "/in.morse").c_str(), "w");
  if (in == nullptr) return false;
  std::fprintf(in,
               "units metal\n"
               "atom_style atomic\n"
               "boundary p p p\n"
               "read_data data.lmp\n"
               "pair_style ${pair} %.17g\n"
               "pair_coeff 1 1 %.17g %.17g %.17g\n"
               "pair_modify shift %s\n"
               "neighbor %.17g bin\n"
               "neigh_modify every 1 delay 0 check yes\n"
               "timestep %.17g\n"
               "fix 1 all nve\n"
               "thermo_style custom step pe ke etotal\n"
               "thermo_modify format float %%.15g\n"
               "thermo %d\n"
               "run %d\n",
               morse.cutoff, morse.d0, morse.alpha, morse.r0, morse.shift ? "yes" : "no", kSkin,
               kDt, kSteps, kSteps);
  std::fclose(in);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string scheme = argc == 3 ? argv[2] : "";
  if (argc < 2 || argc > 3 ||
      (argc == 3 && scheme != "nve" && scheme != "dpd" && scheme != "dpd_gaussian" &&
       scheme != "dpd_uniform" && scheme != "thermostat")) {
    std::fprintf(stderr,
                 "usage: dpd_morse_bench WORK_DIR [nve|dpd|dpd_gaussian|dpd_uniform|thermostat]\n");
    return 2;
  }
  FccCrystal crystal = fcc_crystal(kCells, kCells, kCells, kLattice, kMass);
  assign_maxwell_boltzmann_velocities(crystal.particles, kTemperature, kSeed);
  if (scheme.empty()) {
    if (write_lammps_files(argv[1], crystal, cu_cg_morse_parameters())) return 0;
    std::fprintf(stderr, "dpd_morse_bench: cannot write into %s\n", argv[1]);
    return 1;
  }

  if (scheme == "thermostat") {
    const ThermostatCost c = thermostat_cost(crystal);
    std::printf(
        "# pbms thermostat: %d interleaved windows of 25 steps; totals nve %.3f s, dpd "
        "%.3f s, dpd_gaussian %.3f s\n",
        kSteps / 25, c.nve_seconds, c.uniform_seconds, c.gaussian_seconds);
    // Machine-read by dpd_morse.sh.
    std::printf("THERMOSTAT default %.6f gaussian %.6f\n", c.uniform, c.gaussian);
    return 0;
  }
  // "dpd" draws θ as a stage does by default (DpdPairFriction's noise).
  const PairNoiseDistribution noise = scheme == "dpd_gaussian"  ? PairNoiseDistribution::kGaussian
                                      : scheme == "dpd_uniform" ? PairNoiseDistribution::kUniform
                                                                : DpdPairFriction{}.noise;
  const RunResult r =
      run(crystal, scheme == "nve" ? DpdScheme::kNve : DpdScheme::kVelocityVerlet, noise);
  std::printf("# pbms %s: cpu %.3f s, wall %.3f s, %ld list builds, E_tot %.15g -> %.15g eV\n",
              scheme.c_str(), r.seconds, r.wall_seconds, r.list_builds,
              r.initial_potential + r.initial_kinetic, r.final_potential + r.final_kinetic);
  // Machine-read by dpd_morse.sh.
  std::printf("PBMS %s cpu_s %.6f particle_steps %.0f initial_pe %.15g final_pe %.15g\n",
              scheme.c_str(), r.seconds, static_cast<double>(crystal.particles.size()) * kSteps,
              r.initial_potential, r.final_potential);
  return 0;
}
