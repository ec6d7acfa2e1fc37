// Kinematics of one step for a hypoelastic stress update with the Jaumann
// (co-rotational) rate: sigma_dot = C:D + W sigma - sigma W.
//
// The spin part is integrated with the Hughes-Winget incremental rotation
// (Int. J. Numer. Meth. Eng. 15, 1862, 1980) rather than by adding
// dt (W sigma - sigma W): Q is exactly orthogonal, so a rigid rotation leaves
// every stress invariant unchanged to round-off whatever dt, and the rotation
// angle is second-order accurate where the additive form grows the stress by
// O(dt) per unit angle.
#pragma once

#include "pbms/grid/symmetric_tensor.hpp"

namespace pbms::mpm {

// D = sym(L), the rate of deformation.
inline grid::SymmetricTensor rate_of_deformation(const grid::Mat3& velocity_gradient) {
  return grid::SymmetricTensor::from_matrix(velocity_gradient);
}

// Q = (I - A)^-1 (I + A) with A = dt/2 skew(L). For a skew A with axial
// vector a this closes to I + 2 (A + A^2) / (1 + |a|^2), and |a|^2 = |A|_F^2 / 2.
// Written out over the three independent entries of A: this runs once per
// point and step.
inline grid::Mat3 hughes_winget_rotation(const grid::Mat3& velocity_gradient, double dt) {
  const grid::Mat3& l = velocity_gradient;
  const double c = 0.25 * dt;
  const double a01 = c * (l(0, 1) - l(1, 0));
  const double a02 = c * (l(0, 2) - l(2, 0));
  const double a12 = c * (l(1, 2) - l(2, 1));
  const double s01 = a01 * a01, s02 = a02 * a02, s12 = a12 * a12;
  const double scale = 2.0 / (1.0 + (s01 + s02 + s12));
  // A^2 is symmetric: (A^2)_ij = sum_k A_ik A_kj with A_ji = -A_ij.
  const double q00 = -(s01 + s02), q11 = -(s01 + s12), q22 = -(s02 + s12);
  const double q01 = -a02 * a12, q02 = a01 * a12, q12 = -a01 * a02;
  grid::Mat3 q;
  q << 1.0 + scale * q00, scale * (a01 + q01), scale * (a02 + q02),  //
      scale * (q01 - a01), 1.0 + scale * q11, scale * (a12 + q12),   //
      scale * (q02 - a02), scale * (q12 - a12), 1.0 + scale * q22;
  return q;
}

// Q t Q^T, computing the six independent entries only.
inline grid::SymmetricTensor rotated(const grid::SymmetricTensor& t, const grid::Mat3& rotation) {
  const auto& v = t.voigt;
  const double tm[3][3] = {{v[0], v[5], v[4]}, {v[5], v[1], v[3]}, {v[4], v[3], v[2]}};
  double m[3][3];  // Q t
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      m[i][j] = rotation(i, 0) * tm[0][j] + rotation(i, 1) * tm[1][j] + rotation(i, 2) * tm[2][j];
    }
  }
  const auto r = [&](int i, int j) {
    return m[i][0] * rotation(j, 0) + m[i][1] * rotation(j, 1) + m[i][2] * rotation(j, 2);
  };
  return {{r(0, 0), r(1, 1), r(2, 2), r(1, 2), r(0, 2), r(0, 1)}};
}

}  // namespace pbms::mpm
