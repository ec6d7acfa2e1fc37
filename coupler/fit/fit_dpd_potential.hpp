// Stage kind fit_dpd_potential: NLopt searches a DPD pair style's free
// parameters, dpd_driver judges each candidate at the target temperature,
// and the stage writes the fitted potential as a potential file.
#pragma once

#include "fit/fit_settings.hpp"
#include "stages/coupler_stage.hpp"

namespace pbms::coupler::fit {

class FitDpdPotentialStage : public CouplerStageKind {
 public:
  static config::StageKindSpec spec() { return fit_dpd_potential_spec(); }
  void run(CouplerStageContext& ctx) override;
};

}  // namespace pbms::coupler::fit
