// Isotropic linear elasticity in Lamé form, shared by the elastic and the
// elasto-plastic material so that both mean the same thing by (E, nu).
#pragma once

#include "pbms/grid/symmetric_tensor.hpp"

namespace pbms::mpm {

struct IsotropicElasticity {
  double lambda = 0.0;         // first Lamé parameter
  double shear_modulus = 0.0;  // mu, second Lamé parameter

  // Caller guarantees E > 0 and -1 < nu < 0.5.
  static IsotropicElasticity from_youngs_modulus_and_poisson_ratio(double e, double nu) {
    return {e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu))};
  }

  [[nodiscard]] double bulk_modulus() const { return lambda + 2.0 / 3.0 * shear_modulus; }

  // lambda + 2 mu: the uniaxial-strain stiffness that sets the longitudinal
  // (fastest) wave speed.
  [[nodiscard]] double p_wave_modulus() const { return lambda + 2.0 * shear_modulus; }

  // C : strain, for a strain or a strain increment.
  [[nodiscard]] grid::SymmetricTensor stress_for(const grid::SymmetricTensor& strain) const {
    const double volumetric = lambda * strain.trace();
    const double two_mu = 2.0 * shear_modulus;
    return {{volumetric + two_mu * strain[0], volumetric + two_mu * strain[1],
             volumetric + two_mu * strain[2], two_mu * strain[3], two_mu * strain[4],
             two_mu * strain[5]}};
  }

  // 1/2 stress : C^-1 : stress, split into volumetric and deviatoric parts so
  // that it also holds after plastic flow has changed the deviator.
  [[nodiscard]] double strain_energy_density(const grid::SymmetricTensor& stress) const {
    const double pressure = -stress.trace() / 3.0;
    const grid::SymmetricTensor s = deviator(stress);
    return pressure * pressure / (2.0 * bulk_modulus()) +
           double_contraction(s, s) / (4.0 * shear_modulus);
  }
};

}  // namespace pbms::mpm
