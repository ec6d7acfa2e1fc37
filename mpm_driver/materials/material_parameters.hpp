// Named numeric parameters of a material style and their validation. Every
// refusal is a pbms::Error that names the style, the parameter and what would
// have been accepted, so a user can fix the input without reading the source.
#pragma once

#include <limits>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "pbms/config/param.hpp"

namespace pbms::mpm {

// Values in the units the caller computes in; the registry does no conversion.
using MaterialParameters = std::map<std::string, double>;

// An interval with open or closed ends; NaN is never inside.
struct ParameterRange {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool lower_inclusive = false;
  bool upper_inclusive = false;

  static ParameterRange positive() { return {0.0, kInf, false, false}; }
  static ParameterRange non_negative() { return {0.0, kInf, true, false}; }
  static ParameterRange above(double lower) { return {lower, kInf, false, false}; }
  static ParameterRange open(double lower, double upper) { return {lower, upper, false, false}; }

  [[nodiscard]] bool contains(double value) const;
  // "0 < nu < 0.5" style text with the parameter's name in the middle.
  [[nodiscard]] std::string describe(std::string_view name) const;

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
};

// A style's key with this range as its bounds: the workflow's check (the
// coupler, before any rank starts) and the style's own (ParameterReader,
// check_parameter) come from one ParameterRange.
[[nodiscard]] config::Param ranged(config::Param param, const ParameterRange& range);
// The initial mass density every MPM material kind takes (the body's, not
// the constitutive model's).
[[nodiscard]] config::Param density_param();

// Isotropic elasticity's E and nu (linear_elastic, j2_plasticity): their
// ranges, and their keys with those ranges and nu's default of 0.3.
inline const ParameterRange kYoungsModulusRange = ParameterRange::positive();
// nu = 0.5 would make lambda infinite; nu <= -1 a negative shear modulus.
inline const ParameterRange kPoissonRatioRange = ParameterRange::open(-1.0, 0.5);
[[nodiscard]] std::vector<config::Param> isotropic_elastic_params();

// Throws pbms::Error unless range contains value.
void check_parameter(std::string_view style, std::string_view name, double value,
                     const ParameterRange& range);

// Reads one style's parameter map. Missing required names, values out of
// range, and names the style does not know (typos) are all refused.
class ParameterReader {
 public:
  ParameterReader(std::string_view style, const MaterialParameters& params);

  double required(const std::string& name, const ParameterRange& range);
  double optional(const std::string& name, double fallback, const ParameterRange& range);

  // Throws if params holds a name that no required()/optional() call asked for.
  void reject_unknown() const;

 private:
  double checked(const std::string& name, double value, const ParameterRange& range);

  std::string style_;
  const MaterialParameters& params_;
  std::set<std::string> accepted_;
};

}  // namespace pbms::mpm
