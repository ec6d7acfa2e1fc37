// Hypoelastic isotropic solid: the small-strain Hooke law applied to the rate
// of deformation, made objective with the Jaumann rate. Adequate while elastic
// strains stay small; rotations may be arbitrary.
#pragma once

#include <memory>
#include <string_view>

#include "isotropic_elasticity.hpp"
#include "material_parameters.hpp"
#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/grid/material.hpp"

namespace pbms::mpm {

class LinearElastic final : public grid::Material {
 public:
  static constexpr std::string_view kStyle = "linear_elastic";

  // Throws pbms::Error unless youngs_modulus > 0 and -1 < poisson_ratio < 0.5.
  LinearElastic(double youngs_modulus, double poisson_ratio);

  // Parameters: youngs_modulus, poisson_ratio.
  static std::unique_ptr<grid::Material> create(const MaterialParameters& params);
  // Its material kind: the keys create() reads, with the ranges it accepts.
  static config::MaterialKindSpec spec();

  [[nodiscard]] std::string_view style() const override { return kStyle; }
  void update(const grid::Mat3& velocity_gradient, double dt,
              grid::MaterialPointState& state) const override;
  void update_block(grid::MaterialBlock& block, std::size_t begin, std::size_t end,
                    double dt) const override;
  // sqrt((lambda + 2 mu) / rho).
  [[nodiscard]] double wave_speed(const grid::MaterialPointState& state) const override;
  [[nodiscard]] double stored_energy_density(const grid::MaterialPointState& state) const override;

  [[nodiscard]] const IsotropicElasticity& elasticity() const { return elasticity_; }

 private:
  IsotropicElasticity elasticity_;
};

}  // namespace pbms::mpm
