// A block of material points in structure-of-arrays form for the stress
// update. The solver keeps points as records; for the per-point arithmetic
// of a step (deformation gradient, determinant, rotation, Hooke's law) it
// transposes up to kSize of them here, so that one loop over the block runs
// that arithmetic on a whole SIMD register of points at once instead of one
// point at a time.
#pragma once

#include <cstddef>

#include "pbms/grid/material_point_state.hpp"
#include "pbms/grid/symmetric_tensor.hpp"

namespace pbms::grid {

struct MaterialBlock {
  static constexpr std::size_t kSize = 64;

  // Velocity gradient dv_a/dx_b of point i at L[3 a + b][i].
  alignas(64) double L[9][kSize];
  // MaterialPointState, field by field; stress in SymmetricTensor's Voigt order.
  alignas(64) double stress[6][kSize];
  alignas(64) double density[kSize];
  alignas(64) double plastic_strain[kSize];
  alignas(64) double internal_energy[kSize];

  [[nodiscard]] Mat3 velocity_gradient(std::size_t i) const {
    Mat3 l;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) l(a, b) = L[3 * a + b][i];
    }
    return l;
  }

  void set_velocity_gradient(std::size_t i, const Mat3& l) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) L[3 * a + b][i] = l(a, b);
    }
  }

  [[nodiscard]] MaterialPointState state(std::size_t i) const {
    MaterialPointState s;
    for (int c = 0; c < 6; ++c) s.stress[c] = stress[c][i];
    s.density = density[i];
    s.plastic_strain = plastic_strain[i];
    s.internal_energy = internal_energy[i];
    return s;
  }

  void set_state(std::size_t i, const MaterialPointState& s) {
    for (int c = 0; c < 6; ++c) stress[c][i] = s.stress[c];
    density[i] = s.density;
    plastic_strain[i] = s.plastic_strain;
    internal_energy[i] = s.internal_energy;
  }
};

}  // namespace pbms::grid
