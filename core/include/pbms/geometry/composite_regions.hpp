// Boolean combinations of regions. They are exact set operations on
// contains(), so they inherit the boundary convention of their parts.
#pragma once

#include <vector>

#include "pbms/geometry/region.hpp"

namespace pbms::geometry {

// Inside when inside any part.
class UnionRegion final : public Region {
 public:
  // Throws pbms::Error if there is no part or a part is null.
  explicit UnionRegion(std::vector<RegionPtr> parts);

  [[nodiscard]] bool contains(const Vec3& x) const override;
  // The hull of the parts' boxes.
  [[nodiscard]] Box bounds() const override;

 private:
  std::vector<RegionPtr> parts_;
};

// Inside when inside every part.
class IntersectionRegion final : public Region {
 public:
  // Throws pbms::Error if there is no part or a part is null.
  explicit IntersectionRegion(std::vector<RegionPtr> parts);

  [[nodiscard]] bool contains(const Vec3& x) const override;
  // The overlap of the parts' boxes; empty when they do not overlap.
  [[nodiscard]] Box bounds() const override;

 private:
  std::vector<RegionPtr> parts_;
};

// Inside `base` and not inside `removed`.
class DifferenceRegion final : public Region {
 public:
  // Throws pbms::Error if either region is null.
  DifferenceRegion(RegionPtr base, RegionPtr removed);

  [[nodiscard]] bool contains(const Vec3& x) const override;
  [[nodiscard]] Box bounds() const override { return base_->bounds(); }

 private:
  RegionPtr base_;
  RegionPtr removed_;
};

}  // namespace pbms::geometry
