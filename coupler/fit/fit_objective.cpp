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
  if (surface_) r.surface = relative(j.surface_energy_100, surface_->energy_100);
  return r;
}

std::vector<double> FitObjective::fitted(const Residuals& r) const {
  std::vector<double> out;
  for (size_t i = 0; i < r.isotherm.size(); ++i) {
    if (!isotherm_->held_out[i]) out.push_back(r.isotherm[i]);
  }
  for (const auto& c : r.elastic) {
    if (c) out.push_back(*c);
  }
  if (r.surface) out.push_back(*r.surface);
  return out;
}

std::vector<double> FitObjective::fitted_scales(const Residuals& r) const {
  std::vector<double> out;
  if (isotherm_) {
    const auto& held = isotherm_->held_out;
    const auto n = static_cast<double>(std::count(
        held.begin(), held.begin() + static_cast<std::ptrdiff_t>(r.isotherm.size()), false));
    for (size_t i = 0; i < r.isotherm.size(); ++i) {
      if (!held[i]) out.push_back(std::sqrt(isotherm_->weight / n));
    }
  }
  if (elastic_) {
    const auto n = static_cast<double>(
        std::count_if(r.elastic.begin(), r.elastic.end(), [](const auto& c) { return c; }));
    for (const auto& c : r.elastic) {
      if (c) out.push_back(std::sqrt(elastic_->weight / n));
    }
  }
  if (surface_ && r.surface) out.push_back(std::sqrt(surface_->weight));
  return out;
}

std::vector<double> FitObjective::target_scales() const {
  Residuals every;
  if (isotherm_) every.isotherm.assign(isotherm_->volume_per_atom.size(), 0.0);
  if (elastic_) every.elastic.assign(elastic_modes(*elastic_).size(), 0.0);
  if (surface_) every.surface = 0.0;
  return fitted_scales(every);
}

double FitObjective::value(const Residuals& r) const {
  const std::vector<double> res = fitted(r), scale = fitted_scales(r);
  double total = 0.0;
  for (size_t i = 0; i < res.size(); ++i) total += scale[i] * scale[i] * res[i] * res[i];
  return total;
}

double FitObjective::max_trained(const Residuals& r) const {
  // A target of weight 0 is reported, not trained.
  const std::vector<double> res = fitted(r), scale = fitted_scales(r);
  double m = 0.0;
  for (size_t i = 0; i < res.size(); ++i) {
    if (scale[i] > 0.0) m = std::max(m, std::abs(res[i]));
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
