// The periodic DPD fcc crystal under uniaxial strain along [100], in process
// and without I/O, for the dpd_uniaxial_strain stage: the stress–strain
// relation behind a plane compression wave in a target whose sides cannot
// move (periodic across, as a plate impact), and the weak-shock speeds that
// relation gives.
//
// Why uniaxial strain and not the isotherm P(V): behind a plane front in a
// laterally confined target the crystal is shortened along the wave and
// held across it, and momentum conservation across the front involves
// σ_xx, not the mean pressure. σ_xx = P + (2/3)(deviatoric part), and in a
// cubic crystal at small strain −σ_xx/ε = C11 against K = (C11 + 2 C12)/3
// for the hydrostatic isotherm: 185 against 138 GPa for the copper
// mesoparticle, a 16 % difference in wave speed. Sampling σ_xx directly
// carries the deviatoric part at every amplitude, without a shear
// correction to defend.
//
// The crystal is the cubic one, its x edge shortened by the compression
// ε = 1 − L/L0 and its y, z edges kept; every point of one call has the
// same cells (enough for the neighbour list at the largest compression)
// and the same seed, so the curve is smooth in ε. The stress is the Cauchy
// stress of sample_stress (elastic_constants.hpp); with the lateral edges
// fixed it is also the force per reference area, the quantity the jump
// conditions balance. Stresses are reported relative to the unstrained
// crystal of the same call, so a small residual pressure of the reference
// (a lattice constant not exactly that of zero pressure) does not enter
// the Rayleigh line.
//
// Rayleigh line (mass and momentum across a steady front into the crystal
// at rest): u_p = ε U_s and σ = ρ0 U_s u_p, hence U_s² = σ(ε)/(ρ0 ε). With
// σ(ε) sampled at constant temperature this is the isothermal, not the
// Hugoniot, curve; for weak fronts the two differ by the adiabatic–
// isothermal difference of C11, ~0.3 GPa of 185 (elastic_constants.hpp),
// and by the shock's entropy, third order in ε.
//
// Where σ(ε) is not convex a single front to a state is not stable: where
// the Rayleigh line from rest to ε passes below σ of a weaker state, the
// wave splits, and its leading front is the shock to the state of largest
// U_s among those up to ε, the one whose Rayleigh line is tangent to σ(ε).
// front_speed is that speed. For the copper mesoparticle this matters: its
// 10 Å Morse cutoff lies 0.22 Å inside the (1, 1, 0) a shell, which enters
// it at ε = 4.45 % with an attractive force step that takes ~4.4 GPa off
// the static σ_xx; at 298 K thermal motion smears the step over ε ≈ 2–6 %,
// U_s peaks at ~4.62 km/s near ε ≈ 0.017 (u_p ≈ 80 m/s) and falls to
// ~3.98 km/s at 6 % (docs/dpd-driver.md).
#pragma once

#include <vector>

#include "kernels/pair_style.hpp"
#include "properties/elastic_constants.hpp"

namespace pbms::dpd {

struct UniaxialStrainPoint {
  double compression = 0.0;        // ε = 1 − L/L0 along [100]
  double stress = 0.0;             // −Δσ_xx, GPa, positive in compression
  double stress_error = 0.0;       // GPa, block standard error; 0 when static
  double lateral_stress = 0.0;     // −Δ(σ_yy + σ_zz)/2, GPa
  double shock_speed = 0.0;        // U_s of the Rayleigh line, m/s
  double particle_velocity = 0.0;  // u_p = ε U_s, m/s
  // The leading front's speed of a wave to this state: the largest U_s of
  // this and the weaker states of the call, m/s.
  double front_speed = 0.0;
};

// Mass density (kg/m³) of the fcc crystal of this lattice constant (Å) and
// particle mass (g/mol).
double fcc_density(double lattice_constant, double mass);

// U_s (m/s) of the Rayleigh line from the crystal at rest, density rho0
// (kg/m³), to the state of compression ε and stress (GPa, positive in
// compression). Throws pbms::Error for ε outside (0, 1) or a stress that is
// not positive (no compression front reaches that state).
double rayleigh_shock_speed(double stress_gpa, double rho0, double compression);

// The states of each compression (in (0, 0.3], increasing) of the crystal
// at reference.lattice_constant. Throws pbms::Error for invalid settings,
// compressions outside (0, 0.3] or not increasing, or reference.cells > 0
// too few for the neighbour list at the largest compression; StageFailure
// for a state whose stress is not finite or not compressive.
std::vector<UniaxialStrainPoint> uniaxial_strain_curve(PairStyle& pair,
                                                       const CrystalSpec& reference,
                                                       const ThermalSettings& thermal,
                                                       const std::vector<double>& compressions);

}  // namespace pbms::dpd
