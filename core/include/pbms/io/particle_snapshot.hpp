// One configuration of particles as read from a file, whatever its format,
// so that a stage can start from an H5MD trajectory or a LAMMPS data file
// alike. Particles are in the order of the file (sorted by id for a data
// file); every per-particle vector that is not empty has one entry each.
// Values are in the file's units, not converted: angstrom and angstrom/ps
// for PBMS files and LAMMPS metal units.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace pbms {

struct ParticleSnapshot {
  std::vector<std::int64_t> id;
  // 0-based: LAMMPS type t is species t-1.
  std::vector<int> species;
  std::vector<std::array<double, 3>> x;
  // Zeros when has_velocities is false, so that a caller may index it
  // either way.
  std::vector<std::array<double, 3>> v;
  bool has_velocities = false;
  // Periodic image counts; empty when the file has none.
  std::vector<std::array<int, 3>> image;
  std::array<double, 3> box_lo{0, 0, 0}, box_hi{0, 0, 0};
  std::array<bool, 3> periodic{true, true, true};
  std::int64_t step = 0;
  double time = 0.0;
  // Indexed by species; empty when the file gives no masses.
  std::vector<double> mass_per_type;
};

}  // namespace pbms
