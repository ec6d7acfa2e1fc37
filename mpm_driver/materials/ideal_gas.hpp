// Inviscid ideal gas, the pressure medium of the seed's inclusion and
// sintering cases: P = (gamma - 1) rho e (seed eq. 6.1, e the specific
// internal energy), stress = -P I. No artificial viscosity: strong shocks in
// the gas need one added by the solver.
#pragma once

#include <memory>
#include <string_view>

#include "material_parameters.hpp"
#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/grid/material.hpp"

namespace pbms::mpm {

class IdealGas final : public grid::Material {
 public:
  static constexpr std::string_view kStyle = "ideal_gas";
  static constexpr double kDefaultGamma = 1.4;  // diatomic; the seed's value

  // Throws pbms::Error unless gamma > 1.
  explicit IdealGas(double gamma = kDefaultGamma);

  // Parameters: gamma (optional, default 1.4), the ratio of specific heats.
  static std::unique_ptr<grid::Material> create(const MaterialParameters& params);
  // Its material kind: the keys create() reads, with the ranges it accepts.
  static config::MaterialKindSpec spec();

  [[nodiscard]] std::string_view style() const override { return kStyle; }

  // Adiabatic: only pressure work changes e (de = -P dv, v = 1/rho), taken
  // with the trapezoidal rule between the start-of-step density
  // rho * det(I + L dt) and the end-of-step state.density, so it matches the
  // solver's own volume change exactly and is second order in the step.
  // Shear (tr D = 0) does no work. Needs det(I + L dt) > 0 and compression
  // per step well below a factor (gamma + 1) / (gamma - 1).
  void update(const grid::Mat3& velocity_gradient, double dt,
              grid::MaterialPointState& state) const override;

  // sqrt(gamma P / rho); zero for a gas with no internal energy.
  [[nodiscard]] double wave_speed(const grid::MaterialPointState& state) const override;
  // rho e, the internal energy per unit volume.
  [[nodiscard]] double stored_energy_density(const grid::MaterialPointState& state) const override;
  // Sets e so that the gas holds the given pressure (>= 0) at the given density.
  [[nodiscard]] grid::MaterialPointState initial_state(double density,
                                                       double pressure) const override;

  [[nodiscard]] double pressure(double density, double specific_internal_energy) const {
    return (gamma_ - 1.0) * density * specific_internal_energy;
  }
  [[nodiscard]] double gamma() const { return gamma_; }

 private:
  double gamma_;
};

}  // namespace pbms::mpm
