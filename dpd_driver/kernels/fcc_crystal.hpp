// A perfect face-centred cubic crystal of one particle type filling a
// periodic orthogonal box: the reference state of the mesoparticle copper.
#pragma once

#include <array>

#include "kernels/dpd_particles.hpp"
#include "kernels/orthogonal_box.hpp"

namespace pbms::dpd {

// The four sites of the conventional cubic cell, in lattice constants.
inline constexpr std::array<Vec3, 4> kFccBasis{
    {{0.0, 0.0, 0.0}, {0.5, 0.5, 0.0}, {0.5, 0.0, 0.5}, {0.0, 0.5, 0.5}}};

struct FccCrystal {
  DpdParticles particles;
  OrthogonalBox box;
};

// cells[a] conventional cubic cells of edge lattice_constant (Å) along each
// axis, box from the origin, 4 particles per cell with ids 1, 2, ... and the
// given mass (g/mol), at rest. Throws pbms::Error for a non-positive count
// or lattice constant.
FccCrystal fcc_crystal(int cells_x, int cells_y, int cells_z, double lattice_constant, double mass);

}  // namespace pbms::dpd
