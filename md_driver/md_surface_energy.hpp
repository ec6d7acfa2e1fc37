// md_surface_energy: the (100) surface energy of the MD crystal at 0 K, a
// slab opened along z against the bulk, before and after relaxing the
// atoms. The target the fit's surface term takes from MD.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::md {

class SurfaceEnergyStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::md
