// Reads one frame of an H5MD 1.0/1.1 particles group: the files H5mdWriter
// writes and those of other writers (LAMMPS `dump h5md`, MDAnalysis).
//
// Each element (position, velocity, image, id, species, box/edges) may be a
// time series (a group with step, time and value) or a fixed dataset. The
// frame is chosen on the position series; every other time series must
// have an entry at the same step, except velocity, which is then reported
// absent (LAMMPS writes velocities at their own interval). Box edges may be
// a vector or a diagonal matrix; the box corner is not part of H5MD, so
// box_lo is 0 and box_hi the edges. Files whose creator is "lammps" store
// LAMMPS types as species; they are shifted to 0-based species, as
// read_lammps_data does.
//
// The file is opened read-only through the default (serial) driver, so one
// rank may read it without the others.
#pragma once

#include <cstdint>
#include <string>

#include "pbms/io/particle_snapshot.hpp"

namespace pbms {

// `group`: the name under /particles; empty picks the only group, or the
// first in name order. `frame`: an index into the position series;
// negative counts from the end (-1 is the last frame). Throws pbms::Error
// naming the file and the missing or malformed group, dataset or
// attribute.
ParticleSnapshot read_h5md_particles(const std::string& path, const std::string& group = "",
                                     std::int64_t frame = -1);

}  // namespace pbms
