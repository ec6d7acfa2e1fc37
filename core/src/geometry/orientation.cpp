#include "pbms/geometry/orientation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::geometry {

namespace {

constexpr const char* kAxisNames = "xyz";

using Wide = std::array<std::int64_t, 3>;

// 64-bit, so that large Miller indices cannot overflow the products.
Wide widened(const MillerDirection& m) {
  return {m[0], m[1], m[2]};
}

std::int64_t dot(const Wide& a, const Wide& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Wide cross(const Wide& a, const Wide& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

template <typename V>
std::string bracketed(const V& v) {
  return fmt::format("[{} {} {}]", v[0], v[1], v[2]);
}

}  // namespace

Orientation::Orientation() : Orientation({1, 0, 0}, {0, 1, 0}, {0, 0, 1}) {}

Orientation::Orientation(const MillerDirection& x, const MillerDirection& y,
                         const MillerDirection& z)
    : axes_{x, y, z} {
  std::array<Wide, 3> w{widened(x), widened(y), widened(z)};
  for (int d = 0; d < 3; ++d) {
    if (dot(w[d], w[d]) == 0) {
      throw Error(
          fmt::format("crystal orientation: the direction along {} is [0 0 0]", kAxisNames[d]));
    }
  }
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3;
    const int lo = std::min(a, b);
    const int hi = std::max(a, b);
    if (const auto p = dot(w[lo], w[hi]); p != 0) {
      throw Error(fmt::format(
          "crystal orientation: {} {} and {} {} are not orthogonal (dot product {})",
          kAxisNames[lo], bracketed(axes_[lo]), kAxisNames[hi], bracketed(axes_[hi]), p));
    }
  }
  // Orthogonal, so x cross y is parallel to z; only its sense can be wrong.
  const Wide xy = cross(w[0], w[1]);
  if (dot(xy, w[2]) < 0) {
    throw Error(fmt::format(
        "crystal orientation is left-handed: x {} cross y {} = {} points opposite to z {}; "
        "flip the sign of one axis",
        bracketed(x), bracketed(y), bracketed(xy), bracketed(z)));
  }
  for (int d = 0; d < 3; ++d) {
    length_[d] = std::sqrt(static_cast<double>(dot(w[d], w[d])));
    for (int c = 0; c < 3; ++c) unit_[d][c] = axes_[d][c] / length_[d];
  }
}

Vec3 Orientation::to_box(const Vec3& crystal) const {
  Vec3 out{};
  for (int d = 0; d < 3; ++d) {
    for (int c = 0; c < 3; ++c) out[d] += unit_[d][c] * crystal[c];
  }
  return out;
}

Vec3 Orientation::to_crystal(const Vec3& box) const {
  Vec3 out{};
  for (int c = 0; c < 3; ++c) {
    for (int d = 0; d < 3; ++d) out[c] += unit_[d][c] * box[d];
  }
  return out;
}

}  // namespace pbms::geometry
