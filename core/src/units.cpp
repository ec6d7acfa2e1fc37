#include "pbms/units.hpp"

#include <cctype>
#include <charconv>
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
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
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
  double value = 0.0;
  const auto* begin = s.data();
  const auto* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr == begin) {
    throw Error(fmt::format("'{}' is not a number (with an optional unit)", text));
  }
  const std::string_view unit = trim(std::string_view(ptr, static_cast<size_t>(end - ptr)));
  if (unit.empty()) return value;
  if (d == Dimension::kNone) {
    throw Error(fmt::format("'{}' must be a plain number without a unit", text));
  }
  for (const auto& u : kUnits) {
    if (u.dim == d && u.symbol == unit) return value * u.to_canonical;
  }
  throw Error(fmt::format("unknown unit '{}' in '{}': accepted units are {}", unit, text,
                          accepted_symbols(d)));
}

double to_metal(double value, std::string_view unit) {
  for (const auto& u : kUnits) {
    if (u.symbol == unit) return value * u.to_canonical;
  }
  return value;
}

}  // namespace pbms::units
