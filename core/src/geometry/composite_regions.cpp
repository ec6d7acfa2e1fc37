#include "pbms/geometry/composite_regions.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "pbms/error.hpp"

namespace pbms::geometry {

namespace {

void check_parts(const std::vector<RegionPtr>& parts, const std::string& what) {
  if (parts.empty()) throw Error(what + " needs at least one region");
  for (const auto& p : parts) {
    if (!p) throw Error(what + " got a null region");
  }
}

}  // namespace

UnionRegion::UnionRegion(std::vector<RegionPtr> parts) : parts_(std::move(parts)) {
  check_parts(parts_, "a union");
}

bool UnionRegion::contains(const Vec3& x) const {
  return std::any_of(parts_.begin(), parts_.end(), [&](const auto& p) { return p->contains(x); });
}

Box UnionRegion::bounds() const {
  Box hull;
  bool any = false;
  for (const auto& p : parts_) {
    const Box b = p->bounds();
    if (b.empty()) continue;  // an empty part must not stretch the hull
    if (!any) {
      hull = b;
      any = true;
      continue;
    }
    for (int d = 0; d < 3; ++d) {
      hull.lo[d] = std::min(hull.lo[d], b.lo[d]);
      hull.hi[d] = std::max(hull.hi[d], b.hi[d]);
    }
  }
  if (!any) return parts_.front()->bounds();
  return hull;
}

IntersectionRegion::IntersectionRegion(std::vector<RegionPtr> parts) : parts_(std::move(parts)) {
  check_parts(parts_, "an intersection");
}

bool IntersectionRegion::contains(const Vec3& x) const {
  return std::all_of(parts_.begin(), parts_.end(), [&](const auto& p) { return p->contains(x); });
}

Box IntersectionRegion::bounds() const {
  Box overlap = parts_.front()->bounds();
  for (std::size_t i = 1; i < parts_.size(); ++i) {
    const Box b = parts_[i]->bounds();
    for (int d = 0; d < 3; ++d) {
      overlap.lo[d] = std::max(overlap.lo[d], b.lo[d]);
      overlap.hi[d] = std::min(overlap.hi[d], b.hi[d]);
    }
  }
  return overlap;
}

DifferenceRegion::DifferenceRegion(RegionPtr base, RegionPtr removed)
    : base_(std::move(base)), removed_(std::move(removed)) {
  if (!base_ || !removed_) throw Error("a difference got a null region");
}

bool DifferenceRegion::contains(const Vec3& x) const {
  return base_->contains(x) && !removed_->contains(x);
}

}  // namespace pbms::geometry
