// Particles on a cubic crystal lattice inside a region: the initial positions
// of DPD mesoparticles (fcc) and of atoms, as LAMMPS `create_atoms` would
// place them, but without LAMMPS.
#pragma once

#include <string_view>
#include <vector>

#include "pbms/geometry/orientation.hpp"
#include "pbms/geometry/region.hpp"

namespace pbms::geometry {

// Cubic lattices by their conventional cubic cell: 1, 2 and 4 sites per cell.
enum class LatticeStyle { kSc, kBcc, kFcc };

// "sc", "bcc", "fcc". Throws pbms::Error naming the styles when unknown.
[[nodiscard]] LatticeStyle lattice_style_from_name(std::string_view name);
[[nodiscard]] std::string_view lattice_style_name(LatticeStyle style);
[[nodiscard]] int sites_per_cell(LatticeStyle style);

// Every lattice site inside `region`. A site sits at `origin` (box
// coordinates) and the crystal axes follow `orient`; the cubic cell has edge
// `lattice_constant`. Sites exactly on a face follow the region's boundary
// convention (region.hpp): with the identity orientation a block of n cells
// per axis starting at a site holds exactly sites_per_cell * n^3 sites.
// With a rotated crystal, a site on a face is inside or not up to rounding;
// shift the origin by a fraction of a plane spacing if a count must be exact
// (adjacent blocks still partition the sites exactly).
//
// Order: by z, then y, then x, compared exactly through each site's integer
// plane index rather than its rounded coordinates, so that the order, and the
// ids a caller derives from it, are the same on every machine and rank count.
//
// Throws pbms::Error unless lattice_constant is positive and finite, the
// region's bounds are finite, and the bounds span at most ~1e10 candidate
// sites (a lattice constant in the wrong units; fill per rank instead).
[[nodiscard]] std::vector<Vec3> fill_lattice(LatticeStyle style, const Region& region,
                                             double lattice_constant,
                                             const Orientation& orient = {},
                                             const Vec3& origin = {0.0, 0.0, 0.0});

[[nodiscard]] inline std::vector<Vec3> fill_fcc(const Region& region, double lattice_constant,
                                                const Orientation& orient = {},
                                                const Vec3& origin = {0.0, 0.0, 0.0}) {
  return fill_lattice(LatticeStyle::kFcc, region, lattice_constant, orient, origin);
}

[[nodiscard]] inline std::vector<Vec3> fill_sc(const Region& region, double lattice_constant,
                                               const Orientation& orient = {},
                                               const Vec3& origin = {0.0, 0.0, 0.0}) {
  return fill_lattice(LatticeStyle::kSc, region, lattice_constant, orient, origin);
}

}  // namespace pbms::geometry
