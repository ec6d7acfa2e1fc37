// The DPD engine's share of a stage's checkpoint, the same in every stage
// that runs one (dpd_run, the concurrent stage): its particles and step, and
// with the DPD/MPM-grid model the rigid groups' velocities on the grid.
#pragma once

#include <cstdint>

#include "engine/dpd_engine.hpp"
#include "engine/dpd_grid_step.hpp"
#include "pbms/io/checkpoint_archive.hpp"

namespace pbms::dpd {

// Collective over the engine's ranks (the particles are gathered on rank 0).
// `grid` is null without the grid model.
void put_engine_state(CheckpointArchive& a, const DpdEngine& engine, const DpdGridStep* grid);
// Collective; returns the step the archive was written after.
std::int64_t take_engine_state(const CheckpointArchive& a, DpdEngine& engine, DpdGridStep* grid);

}  // namespace pbms::dpd
