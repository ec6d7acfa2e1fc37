// A symmetric 3x3 tensor (stress, strain rate) kept as its six independent
// components. Six doubles instead of nine keep the per-particle state small,
// make symmetry exact by construction and map one-to-one onto output columns;
// kernels expand to a full Mat3 only where they rotate.
#pragma once

// GCC 12 warns inside its own AVX-512 intrinsics when Eigen uses them
// (GCC bug 105593, fixed in 13); nothing of ours is uninitialised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Core>
#pragma GCC diagnostic pop

#include <array>
#include <cmath>

namespace pbms::grid {

// Velocity gradients, rotations and other general second-order tensors.
using Mat3 = Eigen::Matrix3d;

// Voigt order [xx, yy, zz, yz, xz, xy] with tensor (not engineering) shear
// components, so that a shear entry is the matrix entry itself. LAMMPS
// per-atom stress lists the shears as xy, xz, yz instead: writers reorder.
struct SymmetricTensor {
  std::array<double, 6> voigt{};

  static SymmetricTensor isotropic(double value) { return {{value, value, value, 0.0, 0.0, 0.0}}; }

  // Keeps the symmetric part, so a matrix that is symmetric only up to
  // round-off is accepted without bias.
  static SymmetricTensor from_matrix(const Mat3& m) {
    return {{m(0, 0), m(1, 1), m(2, 2), 0.5 * (m(1, 2) + m(2, 1)), 0.5 * (m(0, 2) + m(2, 0)),
             0.5 * (m(0, 1) + m(1, 0))}};
  }

  [[nodiscard]] Mat3 to_matrix() const {
    const auto& v = voigt;
    Mat3 m;
    m << v[0], v[5], v[4], v[5], v[1], v[3], v[4], v[3], v[2];
    return m;
  }

  double operator[](int i) const { return voigt[static_cast<std::size_t>(i)]; }
  double& operator[](int i) { return voigt[static_cast<std::size_t>(i)]; }

  [[nodiscard]] double trace() const { return voigt[0] + voigt[1] + voigt[2]; }
};

inline SymmetricTensor operator+(const SymmetricTensor& a, const SymmetricTensor& b) {
  SymmetricTensor r;
  for (int i = 0; i < 6; ++i) r[i] = a[i] + b[i];
  return r;
}

inline SymmetricTensor operator*(double s, const SymmetricTensor& a) {
  SymmetricTensor r;
  for (int i = 0; i < 6; ++i) r[i] = s * a[i];
  return r;
}

// a : b. Shear entries appear twice in the full sum, hence the factor 2.
inline double double_contraction(const SymmetricTensor& a, const SymmetricTensor& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

inline SymmetricTensor deviator(const SymmetricTensor& t) {
  const double mean = t.trace() / 3.0;
  return {{t[0] - mean, t[1] - mean, t[2] - mean, t[3], t[4], t[5]}};
}

// sqrt(3/2 s:s), the uniaxial stress with the same distortional energy.
inline double von_mises_stress(const SymmetricTensor& stress) {
  const SymmetricTensor s = deviator(stress);
  return std::sqrt(1.5 * double_contraction(s, s));
}

}  // namespace pbms::grid
