// The primitive solid shapes. See region.hpp for which boundary points are
// inside: planar faces half-open (lo <= x < hi), curved surfaces closed.
#pragma once

#include <array>

#include "pbms/geometry/region.hpp"

namespace pbms::geometry {

// lo <= x < hi on every axis.
class BlockRegion final : public Region {
 public:
  // Throws pbms::Error unless every coordinate is finite and lo < hi on
  // every axis.
  BlockRegion(const Vec3& lo, const Vec3& hi);

  [[nodiscard]] bool contains(const Vec3& x) const override;
  [[nodiscard]] Box bounds() const override { return {lo_, hi_}; }

 private:
  Vec3 lo_;
  Vec3 hi_;
};

// |x - centre| <= radius.
class SphereRegion final : public Region {
 public:
  // Throws pbms::Error unless the centre is finite and radius > 0.
  SphereRegion(const Vec3& centre, double radius);

  [[nodiscard]] bool contains(const Vec3& x) const override;
  [[nodiscard]] Box bounds() const override;

 private:
  Vec3 centre_;
  double radius_;
};

enum class Axis { kX = 0, kY = 1, kZ = 2 };

// A right circular cylinder along a coordinate axis: lo <= x_axis < hi and
// the distance from the axis line <= radius. `centre` holds the two other
// coordinates of the axis line in increasing axis order: (y, z) for an x
// cylinder, (x, z) for y, (x, y) for z -- the order LAMMPS uses.
class CylinderRegion final : public Region {
 public:
  // Throws pbms::Error unless all numbers are finite, radius > 0 and lo < hi.
  CylinderRegion(Axis axis, const std::array<double, 2>& centre, double radius, double lo,
                 double hi);

  [[nodiscard]] bool contains(const Vec3& x) const override;
  [[nodiscard]] Box bounds() const override;

 private:
  int axis_;
  std::array<int, 2> across_;  // the two other axes, increasing
  std::array<double, 2> centre_;
  double radius_;
  double lo_;
  double hi_;
};

}  // namespace pbms::geometry
