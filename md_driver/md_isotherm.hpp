// md_isotherm: NPT molecular dynamics of a periodic crystal at a ladder of
// pressures; averages V, P and the lattice parameter, then fits a
// Birch-Murnaghan equation of state.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::md {

class IsothermStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::md
