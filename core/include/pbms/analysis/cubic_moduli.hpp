// The moduli of a cubic crystal (cube axes along x, y, z) from its three
// elastic constants: what md_elastic, dpd_elastic, the fit's judge and the
// MPM cubic materials report or build from, written once. Any consistent
// units (GPa in the stages, bar in the MPM materials).
#pragma once

namespace pbms::analysis {

struct CubicModuli {
  double c11 = 0.0, c12 = 0.0, c44 = 0.0;

  // (C11 + 2 C12)/3.
  [[nodiscard]] double bulk_modulus() const { return (c11 + 2.0 * c12) / 3.0; }
  // Uniaxial stress along a cube axis: (C11 − C12)(C11 + 2 C12)/(C11 + C12).
  [[nodiscard]] double youngs_modulus_100() const {
    return (c11 - c12) * (c11 + 2.0 * c12) / (c11 + c12);
  }
  // Lateral contraction of that pull: C12/(C11 + C12).
  [[nodiscard]] double poisson_ratio_100() const { return c12 / (c11 + c12); }
  // 2 C44/(C11 − C12): 1 for an isotropic solid, about 3 for copper.
  [[nodiscard]] double zener_ratio() const { return 2.0 * c44 / (c11 - c12); }
  // C′ = (C11 − C12)/2, the modulus of the tetragonal shear.
  [[nodiscard]] double tetragonal_shear_modulus() const { return 0.5 * (c11 - c12); }
  // Positive definite exactly when all three hold.
  [[nodiscard]] bool stable() const { return c44 > 0.0 && c11 > c12 && c11 + 2.0 * c12 > 0.0; }
};

}  // namespace pbms::analysis
