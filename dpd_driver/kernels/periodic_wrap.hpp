// Wrapping positions back into a periodic box, counting each crossing in
// the particle's image so that x + image * L stays the unwrapped position.
#pragma once

#include <cmath>
#include <cstddef>

#include "kernels/dpd_particles.hpp"
#include "kernels/orthogonal_box.hpp"

namespace pbms::dpd {

// Wraps the first `count` particles into [lo, hi) along `axis`.
inline void wrap_axis(DpdParticles& particles, const OrthogonalBox& box, int axis,
                      std::size_t count) {
  const double lo = box.lo[axis];
  const double length = box.length(axis);
  for (std::size_t i = 0; i < count; ++i) {
    double& x = particles.x[i][axis];
    double crossings = std::floor((x - lo) / length);
    if (crossings == 0.0) continue;
    x -= crossings * length;
    if (x >= lo + length) {  // a value just below lo rounds up to hi
      x -= length;
      crossings += 1.0;
    }
    particles.image[i][axis] += static_cast<int>(crossings);
  }
}

// wrap_axis on every periodic axis of the box.
inline void wrap_periodic_axes(DpdParticles& particles, const OrthogonalBox& box,
                               std::size_t count) {
  for (int a = 0; a < 3; ++a) {
    if (box.periodic[a]) wrap_axis(particles, box, a, count);
  }
}

}  // namespace pbms::dpd
