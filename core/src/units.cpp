#include "pbms/units.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::units {
namespace {

struct UnitEntry {
  Dimension dim;
  std::string_view symbol;
  double to_canonical;
};

// Factors to metal units. 1 m/s = 1e10 Å / 1e12 ps = 0.01 Å/ps.
constexpr UnitEntry kUnits[] = {
    {Dimension::kPressure, "bar", 1.0},
    {Dimension::kPressure, "kbar", 1.0e3},
    {Dimension::kPressure, "GPa", 1.0e4},
    {Dimension::kPressure, "MPa", 10.0},
    {Dimension::kPressure, "Pa", 1.0e-5},
    {Dimension::kPressure, "atm", 1.01325},
    {Dimension::kLength, "Å", 1.0},
    {Dimension::kLength, "A", 1.0},
    {Dimension::kLength, "angstrom", 1.0},
    {Dimension::kLength, "nm", 10.0},
    {Dimension::kTime, "ps", 1.0},
    {Dimension::kTime, "fs", 1.0e-3},
    {Dimension::kTime, "ns", 1.0e3},
    {Dimension::kTemperature, "K", 1.0},
    {Dimension::kVelocity, "Å/ps", 1.0},
    {Dimension::kVelocity, "A/ps", 1.0},
    {Dimension::kVelocity, "m/s", 0.01},
    {Dimension::kVelocity, "km/s", 10.0},
    {Dimension::kEnergy, "eV", 1.0},
    {Dimension::kEnergy, "meV", 1.0e-3},
    {Dimension::kMass, "g/mol", 1.0},
    {Dimension::kRate, "1/ps", 1.0},
    {Dimension::kRate, "%/ps", 0.01},
    {Dimension::kRate, "1/ns", 1.0e-3},
    {Dimension::kDensity, "g/cm^3", 1.0},
    {Dimension::kDensity, "kg/m^3", 1.0e-3},
    {Dimension::kAcceleration, "Å/ps^2", 1.0},
    {Dimension::kAcceleration, "A/ps^2", 1.0},
    {Dimension::kAcceleration, "m/s^2", 1.0e-14},
    {Dimension::kForce, "eV/Å", 1.0},
    {Dimension::kForce, "eV/A", 1.0},
    {Dimension::kForce, "nN", 0.6241509074},
    {Dimension::kSurfaceEnergy, "eV/Å^2", 1.0},
    {Dimension::kSurfaceEnergy, "eV/A^2", 1.0},
    {Dimension::kSurfaceEnergy, "J/m^2", 1.0 / kJoulePerM2PerEvPerA2},
    {Dimension::kSurfaceEnergy, "mJ/m^2", 1.0e-3 / kJoulePerM2PerEvPerA2},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// What a dimension measures, for messages.
std::string_view dimension_name(Dimension d) {
  switch (d) {
    case Dimension::kNone:
      return "a plain number";
    case Dimension::kPressure:
      return "a pressure";
    case Dimension::kLength:
      return "a length";
    case Dimension::kTime:
      return "a time";
    case Dimension::kTemperature:
      return "a temperature";
    case Dimension::kVelocity:
      return "a velocity";
    case Dimension::kEnergy:
      return "an energy";
    case Dimension::kMass:
      return "a molar mass";
    case Dimension::kRate:
      return "a rate";
    case Dimension::kDensity:
      return "a density";
    case Dimension::kAcceleration:
      return "an acceleration";
    case Dimension::kForce:
      return "a force";
    case Dimension::kSurfaceEnergy:
      return "an energy per area";
  }
  return "a quantity";
}

bool starts_with_nocase(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  }
  return true;
}

// The user's text in a message, cut if it is long.
std::string quoted(std::string_view text) {
  constexpr size_t kShown = 60;
  return text.size() <= kShown ? fmt::format("'{}'", text)
                               : fmt::format("'{}...'", text.substr(0, kShown));
}

}  // namespace

std::string_view canonical_symbol(Dimension d) {
  switch (d) {
    case Dimension::kNone:
      return "1";
    case Dimension::kPressure:
      return "bar";
    case Dimension::kLength:
      return "Å";
    case Dimension::kTime:
      return "ps";
    case Dimension::kTemperature:
      return "K";
    case Dimension::kVelocity:
      return "Å/ps";
    case Dimension::kEnergy:
      return "eV";
    case Dimension::kMass:
      return "g/mol";
    case Dimension::kRate:
      return "1/ps";
    case Dimension::kDensity:
      return "g/cm^3";
    case Dimension::kAcceleration:
      return "Å/ps^2";
    case Dimension::kForce:
      return "eV/Å";
    case Dimension::kSurfaceEnergy:
      return "eV/Å^2";
  }
  return "?";
}

std::string accepted_symbols(Dimension d) {
  std::string out;
  for (const auto& u : kUnits) {
    if (u.dim != d) continue;
    if (!out.empty()) out += ", ";
    out += u.symbol;
  }
  return out;
}

double parse_quantity(std::string_view text, Dimension d) {
  const std::string_view s = trim(text);
  // YAML's .nan and .inf, and the nan, inf and infinity that from_chars reads.
  std::string_view magnitude = s;
  if (!magnitude.empty() && (magnitude[0] == '+' || magnitude[0] == '-')) {
    magnitude.remove_prefix(1);
  }
  if (starts_with_nocase(magnitude, ".nan") || starts_with_nocase(magnitude, ".inf") ||
      starts_with_nocase(magnitude, "nan") || starts_with_nocase(magnitude, "inf")) {
    throw Error(fmt::format("{} is not a finite number", quoted(text)));
  }
  double value = 0.0;
  const auto* begin = s.data();
  const auto* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range) {
    throw Error(fmt::format("{} is too large or too small for a number", quoted(text)));
  }
  if (ec != std::errc() || ptr == begin) {
    throw Error(fmt::format("{} is not a number (with an optional unit)", quoted(text)));
  }
  if (!std::isfinite(value)) throw Error(fmt::format("{} is not a finite number", quoted(text)));
  const std::string_view unit = trim(std::string_view(ptr, static_cast<size_t>(end - ptr)));
  if (unit.empty()) return value;
  if (d == Dimension::kNone) {
    throw Error(fmt::format("{} must be a plain number without a unit", quoted(text)));
  }
  for (const auto& u : kUnits) {
    if (u.dim == d && u.symbol == unit) return value * u.to_canonical;
  }
  for (const auto& u : kUnits) {
    if (u.symbol == unit) {
      throw Error(fmt::format(
          "'{}' in {} measures {}, but this key takes {}: accepted units "
          "are {}",
          unit, quoted(text), dimension_name(u.dim), dimension_name(d), accepted_symbols(d)));
    }
  }
  throw Error(fmt::format("unknown unit {} in {}: accepted units are {}", quoted(unit),
                          quoted(text), accepted_symbols(d)));
}

double to_metal(double value, std::string_view unit) {
  for (const auto& u : kUnits) {
    if (u.symbol == unit) return value * u.to_canonical;
  }
  return value;
}

}  // namespace pbms::units
