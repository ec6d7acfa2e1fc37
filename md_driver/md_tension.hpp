// md_tension: uniaxial tension of a free-standing nanowire pulled along x by
// two rigid grips; stress from the grip forces, Young's modulus from a line
// fit to the elastic part.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::md {

class TensionStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::md
