// md_elastic: cubic elastic constants C11, C12, C44 from +/- finite strains
// of a relaxed crystal at 0 K, and optionally from NVT stress averages at T.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::md {

class ElasticStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::md
