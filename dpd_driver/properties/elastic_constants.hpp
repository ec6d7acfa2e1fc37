// Cubic elastic constants of the periodic DPD fcc crystal, in process and
// without I/O, for the dpd_elastic stage and for potential fitting (one call
// must be cheap and take everything as arguments).
//
// Method. The crystal is built with axes x' = [110], y' = [−110], z = [001]
// (body-centred tetragonal cells a/√2 × a/√2 × a), because an orthogonal
// periodic box cannot be sheared but this one can be strained
//   tetragonal, diag(1, 1, 1 ± ε):  C11 = dσzz/dεzz, C12 = dσx'x'/dεzz = dσy'y'/dεzz,
//   (1 ± ε, 1 ∓ ε, 1):              the shear ε_xy = ±ε of the cubic axes,
//                                   C44 = d(σx'x' − σy'y')/dε / 4,
// each by a central difference of the Cauchy stress σ = −(Σ m v⊗v + Σ r_ij⊗f_ij)/V
// (positive in tension) of the homogeneously strained crystal. fcc is a
// Bravais lattice, so the strained perfect crystal has no internal
// relaxation: the static stress is exact for many-body styles (Sutton–Chen)
// as for pair potentials. At a pressure P ≠ 0 these are the stress–strain
// coefficients (Wallace) B11 = C11 − P, B12 = C12 + P, B44 = C44 − P, the
// ones that govern wave speeds; at P = 0 they are the elastic constants.
//
// Temperature > 0: each strained state is run by isothermal DPD (velocity
// Verlet with pair friction, DpdScheme::kVelocityVerlet) at fixed box and
// its stress averaged over the sampling steps. The +ε and −ε runs use the
// same seed, so the same initial velocities and the same pair noise: the
// friction pulls the two trajectories together (noise-induced
// synchronisation), and the difference σ(+ε) − σ(−ε) carries little of the
// thermal noise of either: for Morse copper at 298 K the error of C11 is
// 0.05 GPa where independent runs of the same length would give ~0.6. The
// error is the standard error of the difference taken block by block (the
// two runs' block means, strain_states.hpp). These are isothermal constants;
// C11 and C12 at constant entropy are larger by T (∂P/∂T)_V² / c_V (C44 is
// the same), ~0.3 GPa for the copper mesoparticle at 298 K.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "kernels/fcc_crystal.hpp"
#include "kernels/pair_style.hpp"
#include "pbms/analysis/strain_states.hpp"

namespace pbms::dpd {

// A periodic fcc crystal of one particle type.
struct CrystalSpec {
  double lattice_constant = 0.0;  // Å, of the conventional cubic cell
  // At least this many lattice constants along every box edge. 0: the
  // fewest the neighbour list accepts (box edge ≥ 2 × (larger cutoff +
  // skin)) in every state a call builds; the count then depends on the state (compressed
  // states can need more cells), so a fit that wants results smooth in its
  // parameters should fix it.
  int cells = 0;
  double mass = 0.0;  // g/mol; only used at temperature > 0
};

// How a state is sampled. temperature 0 is the static perfect crystal and
// ignores everything else.
//
// The defaults are for the copper mesoparticle (508.37 g/mol, Morse of
// docs/dpd-morse-fit.md), measured in tests/unit/test_dpd_properties.cpp:
// at 298 K the automatic 3 cells (150 particles in the rotated box) give
// C11, C12, C44 with standard errors of ~0.05 GPa (0.03 %) in ~1.5 s, and
// agree with 5 and 6 cells within 0.05 GPa. Accuracy is not the limit: 500
// sampling steps still give ~0.1 %. The stress difference has a weak tail
// of correlations out to ~4 ps, so error blocks shorter than that
// underestimate the error (by ~1/3 at 1 ps); the default blocks are 4 ps.
struct ThermalSettings {
  double temperature = 0.0;  // K
  // g/mol/ps. Sampling only: the canonical averages depend on neither γ nor
  // the DPD cutoff. With the default cutoff the friction rate γ Σ w_D / m is
  // ~20/ps for the copper mesoparticle (0.2 per step): equilibration within
  // 1 ps, tight synchronisation of the ±ε runs, the kinetic temperature
  // within 0.3 % of the bath. At 4 γ particles start to wander (neighbour
  // list rebuilds every ~20 steps instead of once a run).
  double gamma = 1.0e4;
  // Å; 0: the crystal's lattice constant, so that the friction and its
  // costly pair noise (three quarters of a step at a 10 Å cutoff) act on
  // the 12 nearest neighbours only.
  double dpd_cutoff = 0.0;
  double dt = 0.01;  // ps; 0.005 gives the same constants within their errors
  int equilibration_steps = 200;
  int sampling_steps = 2000;
  std::uint64_t seed = 1;
};

// Central differences truncate at O(ε²), and at temperature faster (pairs
// crossing the cutoff, where Morse forces jump): for Morse copper at 298 K,
// C44 is 0.7 GPa low at ε = 0.01, 0.06 at 5e-3 and within its 0.02 GPa
// error at 2e-3. While the ±ε runs stay synchronised the noise of their
// difference shrinks with ε (checked down to 1e-3), so ε is small; static
// stresses have no noise, and only round-off (~1e-12 relative) below.
inline constexpr double kStaticStrain = 1.0e-4;
inline constexpr double kThermalStrain = 2.0e-3;
// Sampling steps the dpd_elastic stage takes by default. The C44 stress
// difference keeps correlations over several ps: with 2,000 steps (blocks
// of 4 ps) the reported C44 error was half the scatter over 10 seeds
// (0.015 against 0.029 GPa); with 8,000 (blocks of 16 ps) the two agree
// (0.008 against 0.007 GPa), DISABLED_DpdPropertiesLong checks it. The
// isotherm keeps ThermalSettings' 2,000: its pressure is one component
// with no such difference, and the fitter calls it often.
inline constexpr int kElasticSamplingSteps = 8000;

// The constants of the crystal at crystal.lattice_constant (at temperature
// usually zero_pressure_lattice_constant's, isotherm.hpp), from ±strain;
// strain 0: kStaticStrain or kThermalStrain. Costs five static evaluations
// (~1 ms for copper) or four DPD runs of equilibration + sampling steps
// (~1 s at ThermalSettings' defaults, ~4 s with kElasticSamplingSteps). Not reentrant for one pair
// style (styles keep per-call state); calls with their own styles may run concurrently. Throws
// pbms::Error for a non-positive lattice constant, a negative cell count, a strain outside [0,
// 0.05], invalid thermal settings, or crystal.cells > 0 too few for the neighbour list.
analysis::ElasticConstants elastic_constants(PairStyle& pair, const CrystalSpec& crystal,
                                             const ThermalSettings& thermal, double strain = 0.0);

// One of the four strained states of elastic_constants on its own: the block
// means of its sampled stress (stress_block_means, strain_states.hpp), for
// elastic_constants_from_states. The same crystal, run and seed as inside
// elastic_constants, so the four states sampled apart (by different rank
// groups of a fit) combine to the same bits as one elastic_constants call.
// Throws as elastic_constants.
std::vector<analysis::CauchyStress> strain_state_stress(PairStyle& pair, const CrystalSpec& crystal,
                                                        const ThermalSettings& thermal,
                                                        analysis::StrainState state,
                                                        double strain = 0.0);

// The strain a call of the two above uses: `strain`, or for 0 kStaticStrain
// at temperature 0 and kThermalStrain above. Throws pbms::Error for a
// strain outside [0, 0.05].
double elastic_strain(const ThermalSettings& thermal, double strain);

// ---- building blocks, shared with isotherm.cpp -------------------------------

// The DPD cutoff (Å) of a crystal of this lattice constant (Å).
double sampling_dpd_cutoff(const ThermalSettings& thermal, double lattice_constant);

// How far (Å) the neighbour list must reach: the larger cutoff plus skin.
// A periodic box edge must be at least twice this.
double sampling_neighbour_reach(const PairStyle& pair, const ThermalSettings& thermal,
                                double lattice_constant);

// The stress of a crystal held in its box (lattice_constant: of its
// unstrained cells, for the DPD cutoff): one row, the static stress, at
// temperature 0; otherwise one row per sampling step after the
// equilibration (Maxwell–Boltzmann velocities at 2T, which equipartition
// brings to T within a phonon period, then DPD at T). Throws pbms::Error
// for a box too small for the neighbour list.
std::vector<analysis::CauchyStress> sample_stress(PairStyle& pair, FccCrystal crystal,
                                                  const ThermalSettings& thermal,
                                                  double lattice_constant);

// Throws pbms::Error, naming the offending field, for invalid settings.
void check_property_settings(const CrystalSpec& crystal, const ThermalSettings& thermal);

}  // namespace pbms::dpd
