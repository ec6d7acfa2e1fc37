// What a material point carries from one step to the next for its
// constitutive model. One struct for every material keeps particle arrays
// homogeneous (a body may switch material per particle) at the price of two
// fields that a given material ignores.
#pragma once

#include "pbms/grid/symmetric_tensor.hpp"

namespace pbms::grid {

struct MaterialPointState {
  SymmetricTensor stress;  // Cauchy stress, tension positive

  // Current mass density. Owned by the solver, which updates it from the
  // deformation (rho <- rho / det(I + L dt), i.e. from det F) before calling
  // Material::update for the same step; materials only read it.
  double density = 0.0;

  double plastic_strain = 0.0;   // equivalent plastic strain (J2 plasticity)
  double internal_energy = 0.0;  // specific internal energy, per unit mass (ideal gas)
};

}  // namespace pbms::grid
