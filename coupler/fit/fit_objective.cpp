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

Residuals FitObjective::residuals(const Judgement& j) const {
  Residuals r;
  if (isotherm_) {
    for (size_t i = 0; i < isotherm_->volume_per_atom.size() && i < j.volume_per_atom.size(); ++i) {
      const double t = isotherm_->volume_per_atom[i];
      r.isotherm.push_back((j.volume_per_atom[i] - t) / t);
    }
  }
  if (elastic_) {
    r.c11 = relative(j.c11, elastic_->c11);
    r.c12 = relative(j.c12, elastic_->c12);
    r.c44 = relative(j.c44, elastic_->c44);
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
    for (const auto& c : {r.c11, r.c12, r.c44}) {
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
  for (const auto& c : {r.c11, r.c12, r.c44}) {
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
