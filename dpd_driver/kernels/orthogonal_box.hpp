// The simulation box of the DPD engine: an orthogonal box whose axes are each
// periodic or not. Pair distances use the minimum image on periodic axes.
#pragma once

#include <array>
#include <cmath>

namespace pbms::dpd {

using Vec3 = std::array<double, 3>;

struct OrthogonalBox {
  Vec3 lo{0.0, 0.0, 0.0};  // Å
  Vec3 hi{0.0, 0.0, 0.0};  // Å
  std::array<bool, 3> periodic{true, true, true};

  [[nodiscard]] double length(int axis) const { return hi[axis] - lo[axis]; }
  [[nodiscard]] double volume() const { return length(0) * length(1) * length(2); }

  // The shortest periodic image of a separation vector. Exact for any
  // separation, not only one within half a box of the answer.
  [[nodiscard]] Vec3 minimum_image(Vec3 d) const {
    for (int a = 0; a < 3; ++a) {
      if (!periodic[a]) continue;
      const double l = length(a);
      d[a] -= l * std::nearbyint(d[a] / l);
    }
    return d;
  }
};

}  // namespace pbms::dpd
