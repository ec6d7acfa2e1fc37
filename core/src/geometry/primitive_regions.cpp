#include "pbms/geometry/primitive_regions.hpp"

#include <cmath>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::geometry {
namespace {

// A curved surface is closed: a site at the radius is inside. Sites at
// exactly the radius in exact arithmetic come out either side of it in
// floating point (a lattice site 3 a from a centre 17 a along: 72.3 - 61.455
// is not 3 x 3.615), so the radius takes a relative allowance far below any
// gap between lattice shells.
double closed_radius_squared(double radius) {
  return radius * radius * (1.0 + 1e-13);
}

constexpr const char* kAxisNames = "xyz";

bool all_finite(const Vec3& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

}  // namespace

BlockRegion::BlockRegion(const Vec3& lo, const Vec3& hi) : lo_(lo), hi_(hi) {
  if (!all_finite(lo) || !all_finite(hi)) {
    throw Error(fmt::format("block corners must be finite, got lo ({}, {}, {}) and hi ({}, {}, {})",
                            lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]));
  }
  for (int d = 0; d < 3; ++d) {
    if (!(lo[d] < hi[d])) {
      throw Error(fmt::format("block needs lo < hi along every axis, got lo {} >= hi {} along {}",
                              lo[d], hi[d], kAxisNames[d]));
    }
  }
}

bool BlockRegion::contains(const Vec3& x) const {
  for (int d = 0; d < 3; ++d) {
    // Written so that NaN compares as outside.
    if (!(x[d] >= lo_[d] && x[d] < hi_[d])) return false;
  }
  return true;
}

SphereRegion::SphereRegion(const Vec3& centre, double radius) : centre_(centre), radius_(radius) {
  if (!all_finite(centre)) {
    throw Error(fmt::format("sphere centre must be finite, got ({}, {}, {})", centre[0], centre[1],
                            centre[2]));
  }
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw Error(fmt::format("sphere radius must be a positive number, got {}", radius));
  }
}

bool SphereRegion::contains(const Vec3& x) const {
  double r2 = 0.0;
  for (int d = 0; d < 3; ++d) r2 += (x[d] - centre_[d]) * (x[d] - centre_[d]);
  return r2 <= closed_radius_squared(radius_);
}

Box SphereRegion::bounds() const {
  Box b;
  for (int d = 0; d < 3; ++d) {
    b.lo[d] = centre_[d] - radius_;
    b.hi[d] = centre_[d] + radius_;
  }
  return b;
}

CylinderRegion::CylinderRegion(Axis axis, const std::array<double, 2>& centre, double radius,
                               double lo, double hi)
    : axis_(static_cast<int>(axis)), centre_(centre), radius_(radius), lo_(lo), hi_(hi) {
  if (axis_ < 0 || axis_ > 2) throw Error("cylinder axis must be x, y or z");
  across_ = {axis_ == 0 ? 1 : 0, axis_ == 2 ? 1 : 2};
  if (!std::isfinite(centre[0]) || !std::isfinite(centre[1])) {
    throw Error(fmt::format("cylinder centre must be finite, got ({}, {})", centre[0], centre[1]));
  }
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw Error(fmt::format("cylinder radius must be a positive number, got {}", radius));
  }
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
    throw Error(
        fmt::format("cylinder needs finite lo < hi along its axis, got lo {} and hi {}", lo, hi));
  }
}

bool CylinderRegion::contains(const Vec3& x) const {
  if (!(x[axis_] >= lo_ && x[axis_] < hi_)) return false;
  const double d0 = x[across_[0]] - centre_[0];
  const double d1 = x[across_[1]] - centre_[1];
  return d0 * d0 + d1 * d1 <= closed_radius_squared(radius_);
}

Box CylinderRegion::bounds() const {
  Box b;
  b.lo[axis_] = lo_;
  b.hi[axis_] = hi_;
  for (int i = 0; i < 2; ++i) {
    b.lo[across_[i]] = centre_[i] - radius_;
    b.hi[across_[i]] = centre_[i] + radius_;
  }
  return b;
}

}  // namespace pbms::geometry
