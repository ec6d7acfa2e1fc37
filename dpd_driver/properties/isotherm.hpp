// Points of the pressure–volume isotherm of the periodic DPD fcc crystal,
// in process and without I/O, for the dpd_isotherm stage and for potential
// fitting: P at a given volume, the volume at a given pressure, and the
// zero-pressure lattice constant.
//
// The crystal is the cubic one (crystal.cells conventional cells per edge)
// scaled uniformly; P = −trace σ / 3 with σ from sample_stress
// (elastic_constants.hpp): static at temperature 0, otherwise the DPD
// average with its block standard error. Inversions solve the static
// problem first, at a fraction of a millisecond per point, and start the
// thermal secant from its root with its slope: the thermal pressure varies
// slowly with volume, so two or three thermal runs usually suffice. All
// runs of one call share thermal.seed, which makes the sampled P(V) nearly
// smooth in V (and in the pair parameters) for the secant to converge on.
//
// Costs for the copper mesoparticle at 298 K and the default settings
// (108 particles): a point ~0.4 s, an inversion ~1 s; static, ~0.3 ms and
// ~2 ms. Not reentrant for one pair style, as elastic_constants.
#pragma once

#include "kernels/pair_style.hpp"
#include "properties/elastic_constants.hpp"

namespace pbms::dpd {

struct IsothermPoint {
  double volume_ratio = 1.0;      // V / V0 of the reference crystal
  double lattice_constant = 0.0;  // Å, of this state
  double pressure = 0.0;          // GPa
  double pressure_error = 0.0;    // GPa, block standard error; 0 when static
};

// The state of volume volume_ratio × V0, V0 that of reference.lattice_constant.
// Throws pbms::Error for invalid settings, a non-positive ratio, or
// reference.cells > 0 too few for the compressed box.
IsothermPoint isotherm_point(PairStyle& pair, const CrystalSpec& reference,
                             const ThermalSettings& thermal, double volume_ratio);

// The state whose pressure is pressure_gpa: static, to 1e-6 GPa (or 1e-6
// in the volume ratio); sampled, to a quarter of the returned
// pressure_error, the statistical error of this seed's P(V). The returned
// pressure is the one reached. Where P(V) is not monotonic the root is the
// one the secant reaches from the reference: for the static Morse copper
// between 6.0 and 10.8 GPa, where the 4th neighbour shell enters the 10 Å
// cutoff and its attractive force jumps in, the larger volume. Throws
// pbms::Error when no state has that pressure: a tension beyond the
// spinodal (−19.5 GPa for the static Morse copper), or a pressure that a
// static P(V) jumps over.
IsothermPoint volume_ratio_at_pressure(PairStyle& pair, const CrystalSpec& reference,
                                       const ThermalSettings& thermal, double pressure_gpa);

// The lattice constant (Å) of zero pressure at thermal.temperature,
// starting from start.lattice_constant: volume_ratio_at_pressure at 0 GPa.
double zero_pressure_lattice_constant(PairStyle& pair, const CrystalSpec& start,
                                      const ThermalSettings& thermal);

}  // namespace pbms::dpd
