#include "engine_checkpoint.hpp"

#include "mpm_model.hpp"

namespace pbms::mpm {

void put_engine_state(CheckpointArchive& a, const MpmEngine& engine) {
  a.put_rows("engine/points", engine.own_rows(), MpmEngine::kStateWidth);
  a.put("engine/step", static_cast<double>(engine.step_count()));
  a.put("engine/point_velocities", point_velocities_of(engine.boundary_conditions()));
}

std::int64_t take_engine_state(const CheckpointArchive& a, MpmEngine& engine) {
  const auto step = static_cast<std::int64_t>(a.scalar("engine/step"));
  engine.restore_state({a.get("engine/points"), a.rank_counts("engine/points")}, step);
  restore_point_velocities(engine.boundary_conditions(), a.get("engine/point_velocities"));
  return step;
}

}  // namespace pbms::mpm
