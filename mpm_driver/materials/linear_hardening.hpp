// Linear isotropic hardening of a von Mises yield surface, shared by the
// isotropic and the cubic J2 materials so that both mean the same thing by
// (yield_stress, hardening_modulus).
#pragma once

namespace pbms::mpm {

struct LinearHardening {
  double yield_stress = 0.0;
  double hardening_modulus = 0.0;

  // Current yield stress at a given equivalent plastic strain.
  [[nodiscard]] double flow_stress(double plastic_strain) const {
    return yield_stress + hardening_modulus * plastic_strain;
  }

  // Plastic work per unit volume, the integral of flow_stress d(eps_p).
  [[nodiscard]] double dissipated_energy_density(double plastic_strain) const {
    return yield_stress * plastic_strain +
           0.5 * hardening_modulus * plastic_strain * plastic_strain;
  }
};

}  // namespace pbms::mpm
