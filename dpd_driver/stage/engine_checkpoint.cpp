#include "engine_checkpoint.hpp"

namespace pbms::dpd {

void put_engine_state(CheckpointArchive& a, const DpdEngine& engine, const DpdGridStep* grid) {
  a.put_rows("engine/particles", engine.own_rows(), DpdEngine::kStateWidth);
  a.put("engine/step", static_cast<double>(engine.step_count()));
  if (grid) a.put("grid/rigid_velocities", grid->rigid_velocities());
}

std::int64_t take_engine_state(const CheckpointArchive& a, DpdEngine& engine, DpdGridStep* grid) {
  const auto step = static_cast<std::int64_t>(a.scalar("engine/step"));
  engine.restore_state({a.get("engine/particles"), a.rank_counts("engine/particles")}, step);
  if (grid) grid->restore_rigid_velocities(a.get("grid/rigid_velocities"));
  return step;
}

}  // namespace pbms::dpd
