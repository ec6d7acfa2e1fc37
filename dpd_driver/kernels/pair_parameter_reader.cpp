#include "kernels/pair_parameter_reader.hpp"

#include <cmath>

#include "pbms/error.hpp"

namespace pbms::dpd {

PairParameterReader::PairParameterReader(std::string_view style, const PairStyleParameters& params)
    : style_(style), params_(params) {}

void PairParameterReader::fail(const std::string& name, const std::string& message) const {
  throw Error("pair style " + style_ + ": " + name + " " + message);
}

double PairParameterReader::required(const std::string& name) {
  accepted_.insert(name);
  const auto it = params_.numbers.find(name);
  if (it == params_.numbers.end()) fail(name, "is required");
  if (!std::isfinite(it->second)) fail(name, "must be a finite number");
  return it->second;
}

double PairParameterReader::required_positive(const std::string& name) {
  const double value = required(name);
  if (!(value > 0.0)) fail(name, "must be > 0, got " + std::to_string(value));
  return value;
}

double PairParameterReader::optional(const std::string& name, double fallback) {
  accepted_.insert(name);
  if (params_.numbers.find(name) == params_.numbers.end()) return fallback;
  return required(name);
}

bool PairParameterReader::optional_flag(const std::string& name, bool fallback) {
  const double value = optional(name, fallback ? 1.0 : 0.0);
  if (value != 0.0 && value != 1.0) fail(name, "must be 0 (no) or 1 (yes)");
  return value == 1.0;
}

std::string PairParameterReader::required_text(const std::string& name) {
  accepted_.insert(name);
  const auto it = params_.texts.find(name);
  if (it == params_.texts.end() || it->second.empty()) fail(name, "is required");
  return it->second;
}

void PairParameterReader::reject_unknown() const {
  for (const auto& [name, value] : params_.numbers) {
    if (accepted_.count(name) == 0) fail(name, "is not a parameter of this style");
  }
  for (const auto& [name, value] : params_.texts) {
    if (accepted_.count(name) == 0) fail(name, "is not a parameter of this style");
  }
}

}  // namespace pbms::dpd
