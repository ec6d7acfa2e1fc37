// dpd_driver as the fit's judge: a candidate potential becomes dpd_isotherm
// requests for the target pressures and, with elastic targets, one
// dpd_elastic request per strained state, all with the run's seed, spread
// over the driver's rank groups. The answers do not depend on which group
// ran them, so a fit gives the same parameters on any number of groups.
#pragma once

#include <optional>

#include <yaml-cpp/yaml.h>

#include "fit/fit_objective.hpp"
#include "fit/fit_settings.hpp"
#include "stages/coupler_stage.hpp"

namespace pbms::coupler::fit {

class DpdJudge {
 public:
  DpdJudge(CouplerStageContext& ctx, const FitSettings& settings)
      : ctx_(ctx), settings_(settings) {}

  // Judges `potential` (a potential map) at `temperature`.
  Judgement judge(const YAML::Node& potential, double temperature);

 private:
  // A request of `kind` for the candidate; `lattice_constant` replaces the
  // material's.
  protocol::RunStage request(const std::string& kind, YAML::Node params,
                             const YAML::Node& potential,
                             std::optional<double> lattice_constant = std::nullopt) const;
  YAML::Node crystal_params(double temperature) const;

  CouplerStageContext& ctx_;
  const FitSettings& settings_;
};

}  // namespace pbms::coupler::fit
