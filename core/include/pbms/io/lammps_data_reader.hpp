// Reads a LAMMPS data file of atom_style atomic (what `write_data` writes
// for it) into a ParticleSnapshot, particles sorted by id.
//
// Understood: the header counts `N atoms` and `N atom types`, the box lines
// `xlo xhi`, `ylo yhi`, `zlo zhi` (LAMMPS's default -0.5 0.5 where one is
// missing), and the sections Masses, Atoms (`id type x y z [ix iy iz]`,
// style comment `# atomic` or none) and Velocities (`id vx vy vz`). Pair
// Coeffs and PairIJ Coeffs sections are skipped: force fields are not part
// of a configuration. Other header counts must be zero.
//
// A data file does not say which axes are periodic (that is the input
// script's `boundary` command), so `periodic` is all true; callers with a
// different boundary set it themselves. Types become 0-based species
// (type t is species t-1, mass_per_type[t-1] its mass); step and time are
// 0. No units are converted.
//
// Refused, as pbms::Error "<path>:<line>: <what>": tilt factors (triclinic
// boxes), other atom styles, wrong column counts, unparsable numbers, types
// outside 1..N atom types, duplicate ids, section lengths that differ from
// the header counts, velocities of unknown ids.
#pragma once

#include <string>

#include "pbms/io/particle_snapshot.hpp"

namespace pbms {

ParticleSnapshot read_lammps_data(const std::string& path);

}  // namespace pbms
