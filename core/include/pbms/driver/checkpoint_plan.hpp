// When a stage writes checkpoints and where it goes on from: the
// workflow's `checkpoint:` map, and the checkpoint a resumed run names.
#pragma once

#include <cstdint>
#include <string>

#include <yaml-cpp/yaml.h>

#include "pbms/config/param.hpp"

namespace pbms {

struct CheckpointPlan {
  std::int64_t every_steps = 0;  // 0: not by steps
  double every_seconds = 0.0;    // wall time; 0: not by time
  int keep = 2;                  // the newest complete ones kept
  std::string resume_from;       // a checkpoint file (absolute); empty: start afresh

  [[nodiscard]] bool enabled() const { return every_steps > 0 || every_seconds > 0.0; }

  // The workflow's `checkpoint:` map, for its schema.
  static config::Param schema();
  // From the resolved map (null: none).
  static CheckpointPlan from_yaml(const YAML::Node& map);
};

}  // namespace pbms
