// dpd_run and dpd_equilibrate: a DPD or DPDE simulation of mesoparticles
// (lattice-filled bodies, or a state read from a file or an earlier stage),
// decomposed over the driver's ranks, with group behaviours (rigid flyers
// and grips, frozen walls), probes, H5MD output and the impact (wave speed)
// and tension (Young's modulus) analyses of seed §5.2.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::dpd {

class DpdRunStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

// The same engine with a Berendsen thermostat on and no analyses; its final
// state is what `initial: {from_stage: ...}` of a later stage starts from.
class DpdEquilibrateStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::dpd
