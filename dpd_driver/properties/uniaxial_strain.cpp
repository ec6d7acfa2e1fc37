#include "properties/uniaxial_strain.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "kernels/fcc_crystal.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

namespace {

// Beyond this the [100] compression of fcc is far along the Bain path and
// the small periodic crystal may leave the fcc branch; a weak front is
// nowhere near it.
constexpr double kMaxCompression = 0.3;

struct SampledStress {
  double xx = 0.0, xx_error = 0.0, lateral = 0.0;
};

SampledStress sample_state(PairStyle& pair, FccCrystal crystal, const ThermalSettings& thermal,
                           double lattice_constant, double compression) {
  const double factor = 1.0 - compression;
  crystal.box.lo[0] *= factor;
  crystal.box.hi[0] *= factor;
  for (auto& x : crystal.particles.x) x[0] *= factor;
  const std::vector<analysis::CauchyStress> samples =
      sample_stress(pair, crystal, thermal, lattice_constant);
  std::vector<double> xx(samples.size()), lateral(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    xx[k] = samples[k][0];
    lateral[k] = 0.5 * (samples[k][1] + samples[k][2]);
  }
  const analysis::BlockAverage s = analysis::block_average(xx, analysis::kStateBlocks);
  return {s.mean, s.error, analysis::block_average(lateral, analysis::kStateBlocks).mean};
}

// The cubic crystal with enough cells along x for the neighbour list at
// the largest compression (and across, at none).
FccCrystal reference_crystal(const PairStyle& pair, const CrystalSpec& reference,
                             const ThermalSettings& thermal, double largest) {
  const double a = reference.lattice_constant;
  const double reach = sampling_neighbour_reach(pair, thermal, a);
  // The margin keeps round-off in the strained box from failing the list's own test.
  const auto needed = [&](double edge) {
    return static_cast<int>(std::ceil(2.0 * reach * (1.0 + 1e-9) / edge));
  };
  const int along = needed(a * (1.0 - largest));
  if (reference.cells > 0 && reference.cells < along) {
    throw Error("DPD uniaxial strain: " + std::to_string(reference.cells) +
                " cells are too few for a neighbour reach of " + std::to_string(reach) +
                " Å at compression " + std::to_string(largest) + "; at least " +
                std::to_string(along) + " (or 0, automatic)");
  }
  const int across = std::max(needed(a), reference.cells);
  return fcc_crystal(std::max(along, reference.cells), across, across, a, reference.mass);
}

}  // namespace

double fcc_density(double lattice_constant, double mass) {
  // 4 particles per cubic cell; g/mol/Å³ to kg/m³.
  return 4.0 * mass / std::pow(lattice_constant, 3) * units::kGramPerCm3PerAmuPerA3 * 1000.0;
}

double rayleigh_shock_speed(double stress_gpa, double rho0, double compression) {
  if (!(compression > 0.0 && compression < 1.0)) {
    throw Error("Rayleigh line: the compression must be in (0, 1)");
  }
  if (!(stress_gpa > 0.0)) {
    throw Error("Rayleigh line: the stress of a compressed state must be > 0 (compressive)");
  }
  return std::sqrt(stress_gpa * 1e9 / (rho0 * compression));
}

std::vector<UniaxialStrainPoint> uniaxial_strain_curve(PairStyle& pair,
                                                       const CrystalSpec& reference,
                                                       const ThermalSettings& thermal,
                                                       const std::vector<double>& compressions) {
  check_property_settings(reference, thermal);
  if (!(reference.mass > 0.0)) throw Error("DPD uniaxial strain: mass must be > 0 g/mol");
  for (std::size_t k = 0; k < compressions.size(); ++k) {
    const double e = compressions[k];
    if (!(e > 0.0 && e <= kMaxCompression) || (k > 0 && !(e > compressions[k - 1]))) {
      throw Error("DPD uniaxial strain: compressions must increase, within (0, " +
                  std::to_string(kMaxCompression) + "]");
    }
  }
  if (compressions.empty()) return {};
  const double largest = compressions.back();
  const FccCrystal crystal = reference_crystal(pair, reference, thermal, largest);
  const double a = reference.lattice_constant;
  const SampledStress rest = sample_state(pair, crystal, thermal, a, 0.0);
  const double rho0 = fcc_density(a, reference.mass);
  std::vector<UniaxialStrainPoint> curve;
  for (const double e : compressions) {
    const SampledStress s = sample_state(pair, crystal, thermal, a, e);
    UniaxialStrainPoint p;
    p.compression = e;
    p.stress = -(s.xx - rest.xx);
    p.stress_error = std::hypot(s.xx_error, rest.xx_error);
    p.lateral_stress = -(s.lateral - rest.lateral);
    if (!std::isfinite(p.stress) || !(p.stress > 0.0)) {
      throw StageFailure("DPD uniaxial strain: the stress at compression " + std::to_string(e) +
                         " is " + std::to_string(p.stress) +
                         " GPa (not compressive: the crystal left the fcc branch)");
    }
    p.shock_speed = rayleigh_shock_speed(p.stress, rho0, e);
    p.particle_velocity = e * p.shock_speed;
    p.front_speed = std::max(p.shock_speed, curve.empty() ? 0.0 : curve.back().front_speed);
    curve.push_back(p);
  }
  return curve;
}

}  // namespace pbms::dpd
