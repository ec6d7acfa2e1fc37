// Linear elasticity of a cubic crystal whose cube axes lie along x, y and z:
// three constants (C11, C12, C44) instead of isotropy's two. The copper
// mesoparticle crystal is strongly anisotropic (2 C44 / (C11 - C12) near 3),
// so an isotropic (E, nu) fitted to its <100> pull has the right static
// response along x but a longitudinal modulus lambda + 2 mu and a shear
// modulus far from the crystal's C11 and C44; whenever waves or the grips'
// lateral hold matter, the two bodies then answer differently.
#pragma once

#include <algorithm>

#include "isotropic_elasticity.hpp"
#include "pbms/analysis/cubic_moduli.hpp"
#include "pbms/grid/symmetric_tensor.hpp"

namespace pbms::mpm {

// The constants and their moduli (bulk, E<100>, nu<100>, stability) are
// analysis::CubicModuli's; this adds the stress they give.
struct CubicElasticity : analysis::CubicModuli {
  // The crystal whose uniaxial [100] pull has Young's modulus e and Poisson
  // ratio nu, with anisotropy zener_ratio = 2 C44 / (C11 - C12): C11 and C12
  // are then isotropy's lambda + 2 mu and lambda, and C44 = zener_ratio mu.
  // Caller guarantees e > 0, -1 < nu < 0.5 and zener_ratio > 0.
  static CubicElasticity from_100(double e, double nu, double zener_ratio) {
    const IsotropicElasticity iso =
        IsotropicElasticity::from_youngs_modulus_and_poisson_ratio(e, nu);
    return {{iso.p_wave_modulus(), iso.lambda, zener_ratio * iso.shear_modulus}};
  }

  // The stiffest longitudinal wave of a cubic crystal runs along <100> or
  // <111> (whichever has the larger modulus); the time step must resolve it.
  [[nodiscard]] double max_longitudinal_modulus() const {
    return std::max(c11, (c11 + 2.0 * c12 + 4.0 * c44) / 3.0);
  }

  // C : strain, with tensor shear components (sigma_xy = 2 C44 eps_xy).
  [[nodiscard]] grid::SymmetricTensor stress_for(const grid::SymmetricTensor& e) const {
    const double t = c12 * e.trace();
    const double d = c11 - c12;
    return {{t + d * e[0], t + d * e[1], t + d * e[2], 2.0 * c44 * e[3], 2.0 * c44 * e[4],
             2.0 * c44 * e[5]}};
  }

  // 1/2 stress : C^-1 : stress. The normal part inverts
  // [c11 c12 c12; ...] through its eigenvalues c11 + 2 c12 (hydrostatic)
  // and c11 - c12 (the two deviatoric normal modes).
  [[nodiscard]] double strain_energy_density(const grid::SymmetricTensor& s) const {
    const double mean = s.trace() / 3.0;
    const grid::SymmetricTensor dev = deviator(s);
    const double normal = 3.0 * mean * mean / (c11 + 2.0 * c12) +
                          (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]) / (c11 - c12);
    const double shear = (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]) / c44;
    return 0.5 * normal + 0.5 * shear;
  }
};

}  // namespace pbms::mpm
