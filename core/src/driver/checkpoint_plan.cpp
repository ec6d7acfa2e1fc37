#include "pbms/driver/checkpoint_plan.hpp"

namespace pbms {

config::Param CheckpointPlan::schema() {
  using config::Param;
  return Param::map(
      "checkpoint",
      {Param::integer("every_steps",
                      "A checkpoint every this many steps of a stage that writes them (dpd_run)")
           .above(0),
       Param::real("every_minutes", units::Dimension::kNone,
                   "A checkpoint once this many minutes of wall time have passed since the last")
           .above(0),
       Param::integer("keep", "The newest complete checkpoints kept; older ones are deleted")
           .def(2)
           .above(0)},
      "Checkpoints of the running stage, for `./pbms run --resume` after a kill or a wall-time "
      "limit (SIGTERM). Each is written at a step boundary under a temporary name and renamed "
      "when complete; the manifest lists the complete ones");
}

CheckpointPlan CheckpointPlan::from_yaml(const YAML::Node& map) {
  CheckpointPlan p;
  if (!map || !map.IsMap()) return p;
  if (map["every_steps"]) p.every_steps = map["every_steps"].as<std::int64_t>();
  if (map["every_minutes"]) p.every_seconds = 60.0 * map["every_minutes"].as<double>();
  if (map["keep"]) p.keep = map["keep"].as<int>();
  return p;
}

}  // namespace pbms
