// md_tension: uniaxial tension along x at a constant strain rate, of a
// free-standing nanowire pulled by two rigid grips (lateral: free), or of a
// crystal periodic in x, y, z stretched by its box with y and z held at zero
// stress (lateral: periodic); Young's modulus from a line fit to the elastic
// part.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::md {

class TensionStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::md
