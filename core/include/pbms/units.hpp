// LAMMPS "metal" units, the only units PBMS computes in, and the conversions
// a user may write in a config ("5 GPa", "2 fs", "3846 m/s").
#pragma once

#include <string>
#include <string_view>

namespace pbms::units {

// Physical constants in metal units.
inline constexpr double kBoltzmann = 8.617333262e-5;  // eV/K
// (g/mol)(Å/ps)^2 -> eV
inline constexpr double kMvv2e = 1.0364269e-4;
inline constexpr double kBarPerGPa = 1.0e4;
// 1 g/mol/Å^3 in g/cm^3: 1e24 / N_A.
inline constexpr double kGramPerCm3PerAmuPerA3 = 1.66053906660;
inline constexpr double kBarPerEvPerA3 = 1.6021766208e6;  // eV/Å^3 -> bar
// eV/Å^2 -> J/m^2: surface energies (the dpd_surface_energy stage).
inline constexpr double kJoulePerM2PerEvPerA2 = 16.021766208;

enum class Dimension {
  kNone,
  kPressure,       // bar
  kLength,         // Å
  kTime,           // ps
  kTemperature,    // K
  kVelocity,       // Å/ps
  kEnergy,         // eV
  kMass,           // g/mol
  kRate,           // 1/ps
  kDensity,        // g/cm^3 (LAMMPS metal); solvers use g/mol/Å^3 = 1/kGramPerCm3PerAmuPerA3
  kAcceleration,   // Å/ps^2
  kForce,          // eV/Å
  kSurfaceEnergy,  // eV/Å^2 (an energy per area, also a line tension's force per length)
};

// Canonical symbol of a dimension in metal units ("bar", "Å", ...).
std::string_view canonical_symbol(Dimension d);

// Parses "5 GPa", "5GPa" or "5" (already canonical) into the canonical unit.
// Throws pbms::Error naming the accepted units when the unit is unknown or of
// the wrong dimension.
double parse_quantity(std::string_view text, Dimension d);

// A value reported in `unit` (a stage result: "87.2 GPa") in metal units,
// so that it can stand where a config key expects one. Symbols that are not
// a unit PBMS converts ("1", "kg/m^3") leave the value as it is.
double to_metal(double value, std::string_view unit);

// The unit symbols a user may write for a dimension, comma separated.
std::string accepted_symbols(Dimension d);

}  // namespace pbms::units
