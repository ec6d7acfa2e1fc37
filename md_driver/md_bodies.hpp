// md_bodies: free-standing crystals of one material, each the lattice sites
// inside a region (the rule DPD bodies are built by), run at a temperature
// with Nose-Hoover NVT and free surfaces; the necks between pairs of them
// over time, measured as the DPD part measures its own (seed §6.4). The MD
// reference for sintering (configs/sintering_md.yaml).
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::md {

class BodiesStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::md
