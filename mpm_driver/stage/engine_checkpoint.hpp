// The MPM engine's share of a stage's checkpoint, the same in every stage
// that runs one (mpm_run, mpm_driver's part of a concurrent stage): its
// points, its step and its held groups' velocities.
#pragma once

#include <cstdint>

#include "engine/mpm_engine.hpp"
#include "pbms/io/checkpoint_archive.hpp"

namespace pbms::mpm {

// Collective over the engine's ranks (the points are gathered on rank 0).
void put_engine_state(CheckpointArchive& a, const MpmEngine& engine);
// Collective; returns the step the archive was written after.
std::int64_t take_engine_state(const CheckpointArchive& a, MpmEngine& engine);

}  // namespace pbms::mpm
