// mpm_driver's part of a concurrent DPD/MPM stage (dpd_driver's
// `concurrent`): the points dpd_driver hands over, as linear elastic
// material points on the shared grid, stepped in lockstep with the DPD
// part under one CouplingScheme. Started by the coupler beside the DPD part,
// with the same parameters; never named by a workflow.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::mpm {

class ConcurrentMpmPart : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::mpm
