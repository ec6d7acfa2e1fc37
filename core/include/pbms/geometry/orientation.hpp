// The orientation of a cubic crystal in the simulation box, given the way
// LAMMPS takes it (`lattice fcc a orient x 1 1 0 orient y -1 1 0 orient z 0 0 1`):
// the crystal direction, as integer Miller indices, that lies along each box
// axis. Integer directions let the lattice builder compute every site's
// plane index exactly, which keeps its ordering free of rounding.
#pragma once

#include <array>

#include "pbms/geometry/region.hpp"

namespace pbms::geometry {

using MillerDirection = std::array<int, 3>;

class Orientation {
 public:
  // The crystal axes along the box axes: [100] [010] [001].
  Orientation();
  // Throws pbms::Error unless every direction is non-zero, the three are
  // mutually orthogonal, and they are right-handed (x cross y along +z), so
  // that a mistyped sign fails loudly instead of mirroring the crystal.
  Orientation(const MillerDirection& x, const MillerDirection& y, const MillerDirection& z);

  // The crystal direction along box axis d (0, 1, 2).
  [[nodiscard]] const MillerDirection& axis(int d) const { return axes_[d]; }
  // Length of axis(d) in units of the lattice constant, sqrt(h^2 + k^2 + l^2).
  [[nodiscard]] double axis_length(int d) const { return length_[d]; }

  // A vector given in crystal coordinates, expressed in box coordinates.
  [[nodiscard]] Vec3 to_box(const Vec3& crystal) const;
  [[nodiscard]] Vec3 to_crystal(const Vec3& box) const;

  bool operator==(const Orientation& other) const { return axes_ == other.axes_; }

 private:
  std::array<MillerDirection, 3> axes_;
  std::array<double, 3> length_;
  std::array<Vec3, 3> unit_;  // rows of the crystal-to-box rotation
};

}  // namespace pbms::geometry
