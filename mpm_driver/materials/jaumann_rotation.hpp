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

#include "symmetric_tensor.hpp"

namespace pbms::mpm {

// D = sym(L), the rate of deformation.
inline SymmetricTensor rate_of_deformation(const Mat3& velocity_gradient) {
  return SymmetricTensor::from_matrix(velocity_gradient);
}

// Q = (I - A)^-1 (I + A) with A = dt/2 skew(L). For a skew A with axial
// vector a this closes to I + 2 (A + A^2) / (1 + |a|^2), and |a|^2 = |A|_F^2 / 2.
inline Mat3 hughes_winget_rotation(const Mat3& velocity_gradient, double dt) {
  const Mat3 a = 0.25 * dt * (velocity_gradient - velocity_gradient.transpose());
  const double scale = 2.0 / (1.0 + 0.5 * a.squaredNorm());
  return Mat3::Identity() + scale * (a + a * a);
}

// Q t Q^T.
inline SymmetricTensor rotated(const SymmetricTensor& t, const Mat3& rotation) {
  return SymmetricTensor::from_matrix(rotation * t.to_matrix() * rotation.transpose());
}

}  // namespace pbms::mpm
