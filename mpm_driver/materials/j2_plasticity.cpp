#include "j2_plasticity.hpp"

#include <cmath>

#include "cubic_j2_plasticity.hpp"
#include "jaumann_rotation.hpp"

namespace pbms::mpm {

namespace {

const ParameterRange kYieldStressRange = ParameterRange::positive();
// Softening (H < 0) makes the local problem ill-posed without regularisation.
const ParameterRange kHardeningModulusRange = ParameterRange::non_negative();
const ParameterRange kZenerRatioRange = ParameterRange::positive();

}  // namespace

J2Plasticity::J2Plasticity(double youngs_modulus, double poisson_ratio, double yield_stress,
                           double hardening_modulus)
    : hardening_{yield_stress, hardening_modulus} {
  check_parameter(kStyle, "youngs_modulus", youngs_modulus, kYoungsModulusRange);
  check_parameter(kStyle, "poisson_ratio", poisson_ratio, kPoissonRatioRange);
  check_parameter(kStyle, "yield_stress", yield_stress, kYieldStressRange);
  check_parameter(kStyle, "hardening_modulus", hardening_modulus, kHardeningModulusRange);
  elasticity_ =
      IsotropicElasticity::from_youngs_modulus_and_poisson_ratio(youngs_modulus, poisson_ratio);
}

config::MaterialKindSpec J2Plasticity::spec() {
  using config::Param;
  using units::Dimension;
  config::MaterialKindSpec s{
      std::string(kStyle),
      "MPM: von Mises plasticity with linear isotropic hardening (radial return)",
      {density_param()}};
  for (auto& p : isotropic_elastic_params()) s.params.push_back(std::move(p));
  s.params.push_back(
      ranged(Param::real("yield_stress", Dimension::kPressure, "Initial yield stress")
                 .require()
                 .referable(),
             kYieldStressRange));
  s.params.push_back(ranged(
      Param::real("hardening_modulus", Dimension::kPressure, "Linear isotropic hardening modulus H")
          .def(0.0)
          .referable(),
      kHardeningModulusRange));
  s.params.push_back(ranged(
      Param::real("zener_ratio", Dimension::kNone,
                  "Anisotropy 2 C44/(C11 - C12) of a cubic crystal with cube axes along x, y, z; "
                  "1 is isotropic. Other values keep E and nu as the [100] pull's and set C44 "
                  "to zener_ratio E/(2 (1 + nu)), e.g. a DPD crystal's "
                  "{from: <dpd_elastic stage>.zener_ratio}")
          .def(1.0)
          .referable(),
      kZenerRatioRange));
  return s;
}

std::unique_ptr<grid::Material> J2Plasticity::create(const MaterialParameters& params) {
  ParameterReader reader(kStyle, params);
  const double e = reader.required("youngs_modulus", kYoungsModulusRange);
  const double nu = reader.required("poisson_ratio", kPoissonRatioRange);
  const double sy = reader.required("yield_stress", kYieldStressRange);
  const double h = reader.optional("hardening_modulus", 0.0, kHardeningModulusRange);
  const double zener_ratio = reader.optional("zener_ratio", 1.0, kZenerRatioRange);
  reader.reject_unknown();
  if (zener_ratio != 1.0) {
    // E and nu stay the [100] pull's; only the shear stiffness C44 departs
    // from isotropy, so the cubic style's cutting-plane return is needed.
    return std::make_unique<CubicJ2Plasticity>(CubicElasticity::from_100(e, nu, zener_ratio), sy, h,
                                               kStyle);
  }
  return std::make_unique<J2Plasticity>(e, nu, sy, h);
}

void J2Plasticity::update(const grid::Mat3& velocity_gradient, double dt,
                          grid::MaterialPointState& state) const {
  const grid::SymmetricTensor strain_increment = dt * rate_of_deformation(velocity_gradient);
  const grid::SymmetricTensor trial =
      rotated(state.stress, hughes_winget_rotation(velocity_gradient, dt)) +
      elasticity_.stress_for(strain_increment);

  const grid::SymmetricTensor s_trial = deviator(trial);
  const double q_trial = std::sqrt(1.5 * double_contraction(s_trial, s_trial));
  const double overstress = q_trial - flow_stress(state.plastic_strain);
  if (overstress <= 0.0) {
    state.stress = trial;
    return;
  }

  // With linear hardening the return along the trial deviator is closed form:
  // q = q_trial - 3 mu dgamma must equal flow_stress(eps_p + dgamma).
  const double mu = elasticity_.shear_modulus;
  const double dgamma = overstress / (3.0 * mu + hardening_.hardening_modulus);
  const double shrink = 1.0 - 3.0 * mu * dgamma / q_trial;
  const double mean = trial.trace() / 3.0;
  state.stress = grid::SymmetricTensor::isotropic(mean) + shrink * s_trial;
  state.plastic_strain += dgamma;
}

double J2Plasticity::wave_speed(const grid::MaterialPointState& state) const {
  return std::sqrt(elasticity_.p_wave_modulus() / state.density);
}

double J2Plasticity::stored_energy_density(const grid::MaterialPointState& state) const {
  return elasticity_.strain_energy_density(state.stress);
}

double J2Plasticity::dissipated_energy_density(const grid::MaterialPointState& state) const {
  return hardening_.dissipated_energy_density(state.plastic_strain);
}

}  // namespace pbms::mpm
