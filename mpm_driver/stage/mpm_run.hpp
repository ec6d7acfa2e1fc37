// mpm_run: an explicit MPM simulation of one or more bodies on a background
// grid, decomposed over the driver's ranks, with probes, H5MD particle and
// XDMF grid output, and the wave-front and vibration analyses the
// verification configs report.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::mpm {

class MpmRunStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::mpm
