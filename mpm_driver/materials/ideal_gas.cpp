#include "ideal_gas.hpp"

// GCC 12 warns inside its own AVX-512 intrinsics when Eigen uses them
// (GCC bug 105593, fixed in 13); nothing of ours is uninitialised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/LU>
#pragma GCC diagnostic pop
#include <algorithm>
#include <cmath>
#include <sstream>

#include "pbms/error.hpp"

namespace pbms::mpm {

namespace {

// gamma = 1 would give a gas without pressure.
const ParameterRange kGammaRange = ParameterRange::above(1.0);

}  // namespace

IdealGas::IdealGas(double gamma) : gamma_(gamma) {
  check_parameter(kStyle, "gamma", gamma, kGammaRange);
}

config::MaterialKindSpec IdealGas::spec() {
  return {std::string(kStyle),
          "MPM: ideal gas P = (gamma - 1) rho e, e from the work of compression",
          {density_param(),
           ranged(config::Param::real("gamma", units::Dimension::kNone, "Ratio of specific heats")
                      .def(kDefaultGamma),
                  kGammaRange)}};
}

std::unique_ptr<grid::Material> IdealGas::create(const MaterialParameters& params) {
  ParameterReader reader(kStyle, params);
  const double gamma = reader.optional("gamma", kDefaultGamma, kGammaRange);
  reader.reject_unknown();
  return std::make_unique<IdealGas>(gamma);
}

void IdealGas::update(const grid::Mat3& velocity_gradient, double dt,
                      grid::MaterialPointState& state) const {
  const double density_end = state.density;
  const double density_start =
      density_end * (grid::Mat3::Identity() + dt * velocity_gradient).determinant();
  const double dv = 1.0 / density_end - 1.0 / density_start;

  // The seed gives only the equation of state (eq. 6.1); the energy balance
  // is the adiabatic one, rho de/dt = sigma : D = -P tr D, here in specific-
  // volume form e1 - e0 = -(P0 + P1)/2 (v1 - v0) with P1 = (gamma - 1) rho1 e1
  // (eq. 6.1), which is linear in e1.
  const double e_start = state.internal_energy;
  const double p_start = pressure(density_start, e_start);
  const double e_end =
      (e_start - 0.5 * p_start * dv) / (1.0 + 0.5 * (gamma_ - 1.0) * density_end * dv);

  state.internal_energy = e_end;
  state.stress = grid::SymmetricTensor::isotropic(-pressure(density_end, e_end));
}

double IdealGas::wave_speed(const grid::MaterialPointState& state) const {
  // gamma P / rho = gamma (gamma - 1) e: independent of density.
  return std::sqrt(std::max(0.0, gamma_ * (gamma_ - 1.0) * state.internal_energy));
}

double IdealGas::stored_energy_density(const grid::MaterialPointState& state) const {
  return state.density * state.internal_energy;
}

grid::MaterialPointState IdealGas::initial_state(double density, double pressure) const {
  grid::MaterialPointState state = grid::Material::initial_state(density, pressure);
  if (!(pressure >= 0.0)) {
    std::ostringstream msg;
    msg << kStyle << ": initial pressure " << pressure
        << " must be >= 0 (a gas cannot hold tension)";
    throw Error(msg.str());
  }
  state.internal_energy = pressure / ((gamma_ - 1.0) * density);
  return state;
}

}  // namespace pbms::mpm
