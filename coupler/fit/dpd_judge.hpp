// dpd_driver as the fit's judge: a candidate potential becomes dpd_isotherm
// requests for the target pressures and, with elastic targets, one
// dpd_elastic request per strained state and, with a surface target, one
// dpd_surface_energy request, all with the run's seed, spread
// over the driver's rank groups. The answers do not depend on which group
// ran them, so a fit gives the same parameters on any number of groups.
#pragma once

#include <map>
#include <optional>
#include <vector>

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
  // What a request answers for: rows of the isotherm targets, the lattice
  // constant of zero pressure, one strained state of the elastic constants,
  // or the static surface energy.
  struct Pending {
    std::vector<size_t> rows;
    bool lattice = false;
    std::optional<size_t> state;
    bool surface = false;
  };
  using Requests = std::map<protocol::RequestId, Pending>;
  using Answers = std::map<protocol::RequestId, Answer>;

  // The requests that can go out at once: the lattice constant of zero
  // pressure (with elastic targets) and the target pressures.
  void submit_isotherms(const YAML::Node& potential, double temperature, Requests& pending) const;
  // Every answer; the strained states go out as the lattice constant they
  // are sampled at comes back.
  Answers collect(const YAML::Node& potential, double temperature, Requests& pending) const;
  // The answers as volumes and elastic constants (metal units).
  [[nodiscard]] Judgement judgement_of(const Requests& pending, const Answers& answers) const;

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
