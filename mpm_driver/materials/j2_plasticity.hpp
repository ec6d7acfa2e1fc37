// Von Mises (J2) elasto-plastic solid with linear isotropic hardening: the
// hypoelastic Jaumann predictor of LinearElastic followed by a radial return
// onto the yield surface sigma_eq = yield_stress + hardening_modulus * eps_p.
// Rate independent; plastic flow is isochoric, so pressure stays elastic.
#pragma once

#include <memory>
#include <string_view>

#include "isotropic_elasticity.hpp"
#include "linear_hardening.hpp"
#include "material_parameters.hpp"
#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/grid/material.hpp"

namespace pbms::mpm {

class J2Plasticity final : public grid::Material {
 public:
  static constexpr std::string_view kStyle = "j2_plasticity";

  // Throws pbms::Error unless youngs_modulus > 0, -1 < poisson_ratio < 0.5,
  // yield_stress > 0 and hardening_modulus >= 0.
  J2Plasticity(double youngs_modulus, double poisson_ratio, double yield_stress,
               double hardening_modulus);

  // Parameters: youngs_modulus, poisson_ratio, yield_stress,
  // hardening_modulus (optional, default 0: perfectly plastic), zener_ratio
  // (optional, default 1: isotropic). A zener_ratio other than 1 makes a
  // cubic crystal with cube axes along x, y, z whose [100] pull has that E
  // and nu (CubicElasticity::from_100), run by CubicJ2Plasticity.
  static std::unique_ptr<grid::Material> create(const MaterialParameters& params);
  // Its material kind: the keys create() reads, with the ranges it accepts.
  static config::MaterialKindSpec spec();

  [[nodiscard]] std::string_view style() const override { return kStyle; }
  void update(const grid::Mat3& velocity_gradient, double dt,
              grid::MaterialPointState& state) const override;
  // The elastic longitudinal speed: the plastic wave is slower, so this bounds both.
  [[nodiscard]] double wave_speed(const grid::MaterialPointState& state) const override;
  [[nodiscard]] double stored_energy_density(const grid::MaterialPointState& state) const override;
  // Plastic work, integral of flow_stress d(eps_p), per unit volume.
  [[nodiscard]] double dissipated_energy_density(
      const grid::MaterialPointState& state) const override;

  [[nodiscard]] double flow_stress(double plastic_strain) const {
    return hardening_.flow_stress(plastic_strain);
  }
  [[nodiscard]] const IsotropicElasticity& elasticity() const { return elasticity_; }

 private:
  IsotropicElasticity elasticity_;
  LinearHardening hardening_;
};

}  // namespace pbms::mpm
