// The region abstraction that the geometry builders fill: a builder asks a
// region only whether a point is inside and where to look, so new shapes need
// no change to any builder.
//
// Boundary convention, shared by every region. Planar faces are half-open:
// lo <= x < hi across every axis-aligned face, so regions stacked face to
// face (two blocks, two cylinder segments along their axis, one block per
// rank) neither share nor lose a lattice site that lies exactly on the face.
// Curved surfaces are closed: a point exactly at the radius is inside, so a
// sphere centred on a lattice site keeps whole neighbour shells and stays
// symmetric. Boolean regions are plain set operations on contains(), so any
// region `a` splits exactly into difference(a, b) and intersection(a, b)
// whatever `b`'s boundary does; use that to cut curved interfaces.
#pragma once

#include <array>
#include <memory>

namespace pbms::geometry {

using Vec3 = std::array<double, 3>;

// An axis-aligned box. As a region's bounds() it is read as the closed box
// [lo, hi], because a closed sphere touches its bounding box.
struct Box {
  Vec3 lo{};
  Vec3 hi{};

  // True when lo > hi on some axis: no point at all, not even a face.
  [[nodiscard]] bool empty() const;
  [[nodiscard]] double volume() const;  // 0 when empty or flat

  bool operator==(const Box&) const = default;
};

class Region {
 public:
  virtual ~Region() = default;

  [[nodiscard]] virtual bool contains(const Vec3& x) const = 0;
  // Every point with contains(x) lies in the closed box [lo, hi]; the box may
  // be larger than the region (for a difference it is the minuend's box).
  [[nodiscard]] virtual Box bounds() const = 0;
};

// Shared and const, so one region can be a part of several composites.
using RegionPtr = std::shared_ptr<const Region>;

}  // namespace pbms::geometry
