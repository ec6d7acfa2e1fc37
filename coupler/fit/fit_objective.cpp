#include "fit/fit_objective.hpp"

#include <algorithm>
#include <cmath>

namespace pbms::coupler::fit {
namespace {

std::optional<double> relative(const std::optional<double>& got,
                               const std::optional<double>& target) {
  if (!got || !target) return std::nullopt;
  return (*got - *target) / *target;
}

}  // namespace

std::vector<ElasticMode> elastic_modes(const ElasticTarget& t) {
  std::vector<ElasticMode> modes;
  if (t.c11 && t.c12) {
    modes = {ElasticMode::kBulk, ElasticMode::kTetragonalShear};
  } else if (t.c11) {
    modes = {ElasticMode::kC11};
  } else if (t.c12) {
    modes = {ElasticMode::kC12};
  }
  if (t.c44) modes.push_back(ElasticMode::kC44);
  return modes;
}

const char* mode_name(ElasticMode m) {
  switch (m) {
    case ElasticMode::kBulk:
      return "bulk_modulus";
    case ElasticMode::kTetragonalShear:
      return "tetragonal_shear_modulus";
    case ElasticMode::kC44:
      return "c44";
    case ElasticMode::kC11:
      return "c11";
    case ElasticMode::kC12:
      return "c12";
  }
  return "";
}

std::optional<double> mode_value(ElasticMode m, const std::optional<double>& c11,
                                 const std::optional<double>& c12,
                                 const std::optional<double>& c44) {
  switch (m) {
    case ElasticMode::kBulk:
      if (c11 && c12) return (*c11 + 2.0 * *c12) / 3.0;
      return std::nullopt;
    case ElasticMode::kTetragonalShear:
      if (c11 && c12) return 0.5 * (*c11 - *c12);
      return std::nullopt;
    case ElasticMode::kC44:
      return c44;
    case ElasticMode::kC11:
      return c11;
    case ElasticMode::kC12:
      return c12;
  }
  return std::nullopt;
}

std::optional<double> mode_error(ElasticMode m, const std::optional<double>& e11,
                                 const std::optional<double>& e12,
                                 const std::optional<double>& e44) {
  const auto sq = [](const std::optional<double>& e) { return e ? *e * *e : 0.0; };
  switch (m) {
    case ElasticMode::kBulk:
      if (e11 || e12) return std::sqrt(sq(e11) + 4.0 * sq(e12)) / 3.0;
      return std::nullopt;
    case ElasticMode::kTetragonalShear:
      if (e11 || e12) return 0.5 * std::sqrt(sq(e11) + sq(e12));
      return std::nullopt;
    case ElasticMode::kC44:
      return e44;
    case ElasticMode::kC11:
      return e11;
    case ElasticMode::kC12:
      return e12;
  }
  return std::nullopt;
}

Residuals FitObjective::residuals(const Judgement& j) const {
  Residuals r;
  if (isotherm_) {
    for (size_t i = 0; i < isotherm_->volume_per_atom.size() && i < j.volume_per_atom.size(); ++i) {
      const double t = isotherm_->volume_per_atom[i];
      r.isotherm.push_back((j.volume_per_atom[i] - t) / t);
    }
  }
  if (elastic_) {
    const ElasticTarget& t = *elastic_;
    for (const ElasticMode m : elastic_modes(t)) {
      r.elastic.push_back(
          relative(mode_value(m, j.c11, j.c12, j.c44), mode_value(m, t.c11, t.c12, t.c44)));
    }
  }
  return r;
}

double FitObjective::value(const Residuals& r) const {
  double total = 0.0;
  if (isotherm_) {
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < r.isotherm.size(); ++i) {
      if (isotherm_->held_out[i]) continue;
      sum += r.isotherm[i] * r.isotherm[i];
      ++n;
    }
    if (n > 0) total += isotherm_->weight * sum / n;
  }
  if (elastic_) {
    double sum = 0.0;
    int n = 0;
    for (const auto& c : r.elastic) {
      if (!c) continue;
      sum += *c * *c;
      ++n;
    }
    if (n > 0) total += elastic_->weight * sum / n;
  }
  return total;
}

double FitObjective::max_trained(const Residuals& r) const {
  double m = 0.0;
  for (size_t i = 0; i < r.isotherm.size(); ++i) {
    if (!isotherm_->held_out[i]) m = std::max(m, std::abs(r.isotherm[i]));
  }
  for (const auto& c : r.elastic) {
    if (c) m = std::max(m, std::abs(*c));
  }
  return m;
}

double FitObjective::max_held_out(const Residuals& r) const {
  double m = 0.0;
  for (size_t i = 0; i < r.isotherm.size(); ++i) {
    if (isotherm_->held_out[i]) m = std::max(m, std::abs(r.isotherm[i]));
  }
  return m;
}

void FailurePenalty::seen(double objective) {
  if (std::isfinite(objective)) worst_ = std::max(worst_, objective);
}

double FailurePenalty::value() const {
  return std::max(1.0, 2.0 * worst_);
}

}  // namespace pbms::coupler::fit
