#include "material_parameters.hpp"

#include <cmath>
#include <sstream>

#include "pbms/error.hpp"

namespace pbms::mpm {

bool ParameterRange::contains(double value) const {
  if (std::isnan(value)) return false;
  const bool above_lower = lower_inclusive ? value >= lower : value > lower;
  const bool below_upper = upper_inclusive ? value <= upper : value < upper;
  return above_lower && below_upper;
}

std::string ParameterRange::describe(std::string_view name) const {
  std::ostringstream out;
  const bool has_lower = std::isfinite(lower);
  const bool has_upper = std::isfinite(upper);
  if (has_lower) out << lower << (lower_inclusive ? " <= " : " < ");
  out << name;
  if (has_upper) out << (upper_inclusive ? " <= " : " < ") << upper;
  if (!has_lower && !has_upper) out << " finite";
  return out.str();
}

config::Param ranged(config::Param param, const ParameterRange& range) {
  if (std::isfinite(range.lower)) {
    if (range.lower_inclusive) {
      param.at_least(range.lower);
    } else {
      param.above(range.lower);
    }
  }
  if (std::isfinite(range.upper)) {
    if (range.upper_inclusive) {
      param.at_most(range.upper);
    } else {
      param.below(range.upper);
    }
  }
  return param;
}

config::Param density_param() {
  // Metal units (g/cm^3 written, g/mol/Å^3 inside) unless a stage runs in
  // `units: consistent`, where the numbers are of one consistent system.
  return config::Param::real("density", units::Dimension::kDensity, "Initial mass density")
      .require()
      .above(0)
      .referable();
}

std::vector<config::Param> isotropic_elastic_params() {
  using config::Param;
  using units::Dimension;
  return {
      ranged(Param::real("youngs_modulus", Dimension::kPressure, "Young's modulus E")
                 .require()
                 .referable(),
             kYoungsModulusRange),
      ranged(Param::real("poisson_ratio", Dimension::kNone, "Poisson's ratio").def(0.3).referable(),
             kPoissonRatioRange)};
}

void check_parameter(std::string_view style, std::string_view name, double value,
                     const ParameterRange& range) {
  if (range.contains(value) && std::isfinite(value)) return;
  std::ostringstream msg;
  msg << style << ": parameter '" << name << "' = " << value << " is outside the accepted range "
      << range.describe(name);
  throw Error(msg.str());
}

ParameterReader::ParameterReader(std::string_view style, const MaterialParameters& params)
    : style_(style), params_(params) {}

double ParameterReader::checked(const std::string& name, double value,
                                const ParameterRange& range) {
  check_parameter(style_, name, value, range);
  return value;
}

double ParameterReader::required(const std::string& name, const ParameterRange& range) {
  accepted_.insert(name);
  const auto it = params_.find(name);
  if (it == params_.end()) {
    throw Error(style_ + ": missing parameter '" + name + "' (accepted range " +
                range.describe(name) + ")");
  }
  return checked(name, it->second, range);
}

double ParameterReader::optional(const std::string& name, double fallback,
                                 const ParameterRange& range) {
  accepted_.insert(name);
  const auto it = params_.find(name);
  return checked(name, it == params_.end() ? fallback : it->second, range);
}

void ParameterReader::reject_unknown() const {
  for (const auto& [name, value] : params_) {
    if (accepted_.count(name) != 0) continue;
    std::string list;
    for (const auto& a : accepted_) list += (list.empty() ? "" : ", ") + a;
    throw Error(style_ + ": unknown parameter '" + name + "'; accepted parameters: " + list);
  }
}

}  // namespace pbms::mpm
