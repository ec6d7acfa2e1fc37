// Von Mises (J2) plasticity with linear isotropic hardening on a cubic
// elastic crystal (CubicElasticity, cube axes along x, y, z). The elastic
// predictor is J2Plasticity's hypoelastic Jaumann step with the cubic
// stiffness; the crystal axes stay fixed to the grid, which is exact while
// lattice rotations stay small (a pull or an impact along a cube axis) and
// an approximation under large rotations. Because C : n is not parallel to
// the flow direction n, the return to the yield surface has no closed form:
// it is the cutting-plane iteration of Simo and Ortiz (1985), which for an
// isotropic C ends after the first step with J2Plasticity's radial return.
#pragma once

#include <memory>
#include <string_view>

#include "cubic_elasticity.hpp"
#include "linear_hardening.hpp"
#include "material_parameters.hpp"
#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/grid/material.hpp"

namespace pbms::mpm {

class CubicJ2Plasticity final : public grid::Material {
 public:
  static constexpr std::string_view kStyle = "cubic_j2_plasticity";

  // Throws pbms::Error unless the stiffness is positive definite,
  // yield_stress > 0 and hardening_modulus >= 0. `style` names the material
  // in errors and style(): j2_plasticity with a zener_ratio builds one too,
  // and its user should read the kind they wrote.
  CubicJ2Plasticity(CubicElasticity elasticity, double yield_stress, double hardening_modulus,
                    std::string_view style = kStyle);

  // Parameters: c11, c12, c44, yield_stress, hardening_modulus (optional,
  // default 0: perfectly plastic).
  static std::unique_ptr<grid::Material> create(const MaterialParameters& params);
  // Its material kind: the keys create() reads, with the ranges it accepts.
  static config::MaterialKindSpec spec();

  [[nodiscard]] std::string_view style() const override { return style_; }
  void update(const grid::Mat3& velocity_gradient, double dt,
              grid::MaterialPointState& state) const override;
  // The fastest elastic longitudinal wave (<100> or <111>).
  [[nodiscard]] double wave_speed(const grid::MaterialPointState& state) const override;
  [[nodiscard]] double stored_energy_density(const grid::MaterialPointState& state) const override;
  [[nodiscard]] double dissipated_energy_density(
      const grid::MaterialPointState& state) const override;

  [[nodiscard]] double flow_stress(double plastic_strain) const {
    return hardening_.flow_stress(plastic_strain);
  }
  [[nodiscard]] const CubicElasticity& elasticity() const { return elasticity_; }

 private:
  // Moves a trial stress outside the yield surface back onto it.
  void return_to_yield_surface(grid::SymmetricTensor& stress, double& plastic_strain) const;

  CubicElasticity elasticity_;
  LinearHardening hardening_;
  std::string_view style_;
};

}  // namespace pbms::mpm
