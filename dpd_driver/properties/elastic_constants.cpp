#include "properties/elastic_constants.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "integrators/dpd_integrator.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/maxwell_boltzmann_velocities.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

namespace {

constexpr double kGpaPerEvPerA3 = units::kBarPerEvPerA3 / units::kBarPerGPa;
// Only ever costs a rebuild when too small (never a result), and every
// 0.1 Å of it adds ~0.2 Å to the smallest box: thermal displacements at
// room temperature are ~0.05 Å, so 0.5 Å rebuilds rarely and lets the
// 10 Å copper cutoff run in 3 cells.
constexpr double kSkin = 0.5;

bool is_static(const ThermalSettings& thermal) {
  return thermal.temperature == 0.0;
}

// Positions and box scaled by (1 + strain[a]) along each axis: the
// homogeneous strain, affine on the particles.
void apply_strain(FccCrystal& crystal, const Vec3& strain) {
  for (int a = 0; a < 3; ++a) {
    const double factor = 1.0 + strain[a];
    crystal.box.lo[a] *= factor;
    crystal.box.hi[a] *= factor;
    for (auto& x : crystal.particles.x) x[a] *= factor;
  }
}

// fcc with x' = [110], y' = [−110], z = [001]: body-centred tetragonal cells
// a/√2 × a/√2 × a with two particles, (0,0,0) and (½,½,½).
FccCrystal rotated_fcc(int cells_xy, int cells_z, double lattice_constant, double mass) {
  const double side = lattice_constant / std::numbers::sqrt2;
  FccCrystal crystal;
  crystal.box.hi = {cells_xy * side, cells_xy * side, cells_z * lattice_constant};
  crystal.particles.mass_per_type = {mass};
  std::int64_t id = 1;
  for (int k = 0; k < cells_z; ++k) {
    for (int j = 0; j < cells_xy; ++j) {
      for (int i = 0; i < cells_xy; ++i) {
        crystal.particles.add(id++, 0, {i * side, j * side, k * lattice_constant});
        crystal.particles.add(id++, 0,
                              {(i + 0.5) * side, (j + 0.5) * side, (k + 0.5) * lattice_constant});
      }
    }
  }
  return crystal;
}

// The fewest cells of edge `edge` that keep a box, shrunk by `shrink`, at
// least 2 reach long, and no fewer than `at_least`.
int cells_for(double edge, double shrink, double reach, int at_least) {
  // The margin keeps round-off in the strained box from failing the list's own test.
  const int needed = static_cast<int>(std::ceil(2.0 * reach * (1.0 + 1e-9) / (edge * shrink)));
  return std::max(needed, at_least);
}

analysis::CauchyStress instantaneous_stress(const DpdParticles& particles, const PairResult& pair,
                                            double volume) {
  std::array<double, 6> kinetic{};
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3& v = particles.v[i];
    const double m = particles.mass(i);
    kinetic[0] += m * v[0] * v[0];
    kinetic[1] += m * v[1] * v[1];
    kinetic[2] += m * v[2] * v[2];
    kinetic[3] += m * v[0] * v[1];
    kinetic[4] += m * v[0] * v[2];
    kinetic[5] += m * v[1] * v[2];
  }
  analysis::CauchyStress s{};
  const double scale = -kGpaPerEvPerA3 / volume;
  for (int c = 0; c < 6; ++c) s[c] = scale * (kinetic[c] * units::kMvv2e + pair.virial[c]);
  return s;
}

// The rotated crystal of elastic_constants at crystal.lattice_constant, with
// enough cells for the neighbour list at `strain` in every state.
FccCrystal reference_crystal(const PairStyle& pair, const CrystalSpec& crystal,
                             const ThermalSettings& thermal, double strain) {
  const double a = crystal.lattice_constant;
  const double reach = sampling_neighbour_reach(pair, thermal, a);
  const int at_least_z = crystal.cells;
  const int at_least_xy = static_cast<int>(std::ceil(crystal.cells * std::numbers::sqrt2 - 1e-9));
  const int cells_z = cells_for(a, 1.0 - strain, reach, at_least_z);
  const int cells_xy = cells_for(a / std::numbers::sqrt2, 1.0 - strain, reach, at_least_xy);
  if (crystal.cells > 0 && crystal.cells < cells_z) {
    throw Error("DPD elastic constants: " + std::to_string(crystal.cells) +
                " cells are too few for a neighbour reach of " + std::to_string(reach) +
                " Å at strain " + std::to_string(strain) + "; at least " + std::to_string(cells_z) +
                " (or 0, automatic)");
  }
  return rotated_fcc(cells_xy, cells_z, a, crystal.mass);
}

// The stress samples of `reference` strained by `e`.
std::vector<analysis::CauchyStress> run_strained(PairStyle& pair, const FccCrystal& reference,
                                                 const ThermalSettings& thermal,
                                                 double lattice_constant, const Vec3& e) {
  FccCrystal strained = reference;
  apply_strain(strained, e);
  return sample_stress(pair, std::move(strained), thermal, lattice_constant);
}

}  // namespace

double sampling_dpd_cutoff(const ThermalSettings& thermal, double lattice_constant) {
  return thermal.dpd_cutoff > 0.0 ? thermal.dpd_cutoff : lattice_constant;
}

double sampling_neighbour_reach(const PairStyle& pair, const ThermalSettings& thermal,
                                double lattice_constant) {
  if (is_static(thermal)) return pair.cutoff();
  return std::max(pair.cutoff(), sampling_dpd_cutoff(thermal, lattice_constant)) + kSkin;
}

void check_property_settings(const CrystalSpec& crystal, const ThermalSettings& thermal) {
  const std::string where = "DPD crystal properties: ";
  if (!(crystal.lattice_constant > 0.0)) throw Error(where + "lattice_constant must be > 0 Å");
  if (crystal.cells < 0) throw Error(where + "cells must be >= 0 (0: automatic)");
  if (!(thermal.temperature >= 0.0)) throw Error(where + "temperature must be >= 0 K");
  if (is_static(thermal)) return;
  if (!(crystal.mass > 0.0)) throw Error(where + "mass must be > 0 g/mol at temperature > 0");
  if (!(thermal.gamma > 0.0)) throw Error(where + "gamma must be > 0 g/mol/ps");
  if (!(thermal.dpd_cutoff >= 0.0)) {
    throw Error(where + "dpd_cutoff must be >= 0 Å (0: the lattice constant)");
  }
  if (!(thermal.dt > 0.0)) throw Error(where + "dt must be > 0 ps");
  if (thermal.equilibration_steps < 0) throw Error(where + "equilibration_steps must be >= 0");
  if (thermal.sampling_steps < analysis::kStateBlocks) {
    throw Error(where + "sampling_steps must be >= " + std::to_string(analysis::kStateBlocks) +
                " (one per error block)");
  }
}

std::vector<analysis::CauchyStress> sample_stress(PairStyle& pair, FccCrystal crystal,
                                                  const ThermalSettings& thermal,
                                                  double lattice_constant) {
  DpdParticles& particles = crystal.particles;
  const double volume = crystal.box.volume();
  if (is_static(thermal)) {
    HalfNeighbourList list(pair.cutoff(), 0.0);
    list.build(particles, crystal.box);
    particles.zero_forces();
    return {instantaneous_stress(particles, pair.compute(particles, list, Tally::kEnergyAndVirial),
                                 volume)};
  }
  assign_maxwell_boltzmann_velocities(particles, 2.0 * thermal.temperature, thermal.seed);
  DpdIntegratorSettings settings;
  settings.scheme = DpdScheme::kVelocityVerlet;
  settings.dt = thermal.dt;
  settings.skin = kSkin;
  settings.friction = {thermal.gamma, sampling_dpd_cutoff(thermal, lattice_constant),
                       thermal.temperature, thermal.seed};
  DpdIntegrator integrator(particles, crystal.box, pair, settings);
  for (int s = 0; s < thermal.equilibration_steps; ++s) integrator.step();
  std::vector<analysis::CauchyStress> samples;
  samples.reserve(static_cast<std::size_t>(thermal.sampling_steps));
  for (int s = 0; s < thermal.sampling_steps; ++s) {
    const PairResult result = integrator.step(Tally::kEnergyAndVirial);
    samples.push_back(instantaneous_stress(particles, result, volume));
  }
  return samples;
}

double elastic_strain(const ThermalSettings& thermal, double strain) {
  if (!(strain >= 0.0 && strain <= 0.05)) {
    throw Error("DPD elastic constants: strain must be in [0, 0.05] (0: the default)");
  }
  if (strain == 0.0) return is_static(thermal) ? kStaticStrain : kThermalStrain;
  return strain;
}

std::vector<analysis::CauchyStress> strain_state_stress(PairStyle& pair, const CrystalSpec& crystal,
                                                        const ThermalSettings& thermal,
                                                        analysis::StrainState state,
                                                        double strain) {
  check_property_settings(crystal, thermal);
  strain = elastic_strain(thermal, strain);
  const FccCrystal reference = reference_crystal(pair, crystal, thermal, strain);
  return analysis::stress_block_means(run_strained(
      pair, reference, thermal, crystal.lattice_constant, analysis::strain_of(state, strain)));
}

analysis::ElasticConstants elastic_constants(PairStyle& pair, const CrystalSpec& crystal,
                                             const ThermalSettings& thermal, double strain) {
  check_property_settings(crystal, thermal);
  strain = elastic_strain(thermal, strain);
  const FccCrystal reference = reference_crystal(pair, crystal, thermal, strain);
  const double a = crystal.lattice_constant;
  // The four states one after the other, each reduced to its block means
  // as strain_state_stress does, so that a fit sampling them apart gets
  // these bits.
  std::array<std::vector<analysis::CauchyStress>, 4> blocks;
  for (std::size_t i = 0; i < analysis::kStrainStates.size(); ++i) {
    blocks[i] = analysis::stress_block_means(run_strained(
        pair, reference, thermal, a, analysis::strain_of(analysis::kStrainStates[i], strain)));
  }
  analysis::ElasticConstants result = analysis::elastic_constants_from_states(blocks, strain);
  if (is_static(thermal)) {
    result.pressure =
        analysis::pressure_of(run_strained(pair, reference, thermal, a, {0.0, 0.0, 0.0}).front());
  }
  return result;
}

}  // namespace pbms::dpd
