#include "linear_elastic.hpp"

#include <cmath>

#include "jaumann_rotation.hpp"

namespace pbms::mpm {

LinearElastic::LinearElastic(double youngs_modulus, double poisson_ratio) {
  check_parameter(kStyle, "youngs_modulus", youngs_modulus, kYoungsModulusRange);
  check_parameter(kStyle, "poisson_ratio", poisson_ratio, kPoissonRatioRange);
  elasticity_ =
      IsotropicElasticity::from_youngs_modulus_and_poisson_ratio(youngs_modulus, poisson_ratio);
}

config::MaterialKindSpec LinearElastic::spec() {
  config::MaterialKindSpec s{std::string(kStyle),
                             "MPM: isotropic linear elasticity, small strain with a Jaumann rate",
                             {density_param()}};
  for (auto& p : isotropic_elastic_params()) s.params.push_back(std::move(p));
  return s;
}

std::unique_ptr<grid::Material> LinearElastic::create(const MaterialParameters& params) {
  ParameterReader reader(kStyle, params);
  const double e = reader.required("youngs_modulus", kYoungsModulusRange);
  const double nu = reader.required("poisson_ratio", kPoissonRatioRange);
  reader.reject_unknown();
  return std::make_unique<LinearElastic>(e, nu);
}

namespace {

[[gnu::always_inline]] inline void update_one(const IsotropicElasticity& elasticity,
                                              const grid::Mat3& velocity_gradient, double dt,
                                              grid::MaterialPointState& state) {
  const grid::SymmetricTensor strain_increment = dt * rate_of_deformation(velocity_gradient);
  state.stress = rotated(state.stress, hughes_winget_rotation(velocity_gradient, dt)) +
                 elasticity.stress_for(strain_increment);
}

}  // namespace

void LinearElastic::update(const grid::Mat3& velocity_gradient, double dt,
                           grid::MaterialPointState& state) const {
  update_one(elasticity_, velocity_gradient, dt, state);
}

void LinearElastic::update_block(grid::MaterialBlock& block, std::size_t begin, std::size_t end,
                                 double dt) const {
  const IsotropicElasticity elasticity = elasticity_;
  for (std::size_t i = begin; i < end; ++i) {
    grid::MaterialPointState s;
    for (int c = 0; c < 6; ++c) s.stress[c] = block.stress[c][i];
    update_one(elasticity, block.velocity_gradient(i), dt, s);
    for (int c = 0; c < 6; ++c) block.stress[c][i] = s.stress[c];
  }
}

double LinearElastic::wave_speed(const grid::MaterialPointState& state) const {
  return std::sqrt(elasticity_.p_wave_modulus() / state.density);
}

double LinearElastic::stored_energy_density(const grid::MaterialPointState& state) const {
  return elasticity_.strain_energy_density(state.stress);
}

}  // namespace pbms::mpm
