#include "cubic_j2_plasticity.hpp"

#include <cmath>

#include <fmt/format.h>

#include "jaumann_rotation.hpp"
#include "pbms/error.hpp"

namespace pbms::mpm {

namespace {

const ParameterRange kModulusRange = ParameterRange::positive();
// C12 may be negative; stability is checked on the three together.
const ParameterRange kAnyFiniteRange{};
const ParameterRange kYieldStressRange = ParameterRange::positive();
const ParameterRange kHardeningModulusRange = ParameterRange::non_negative();

// The cutting plane converges linearly at a rate set by the anisotropy; a
// copper-like crystal (2 C44 / (C11 - C12) = 3) needs about ten passes to
// 1e-12. The cap only guards against a stiffness that makes it diverge.
constexpr int kMaxReturnIterations = 200;
constexpr double kReturnTolerance = 1e-12;

}  // namespace

CubicJ2Plasticity::CubicJ2Plasticity(CubicElasticity elasticity, double yield_stress,
                                     double hardening_modulus, std::string_view style)
    : elasticity_(elasticity), hardening_{yield_stress, hardening_modulus}, style_(style) {
  check_parameter(style_, "yield_stress", yield_stress, kYieldStressRange);
  check_parameter(style_, "hardening_modulus", hardening_modulus, kHardeningModulusRange);
  if (!elasticity_.stable()) {
    throw Error(fmt::format(
        "{}: c11 = {}, c12 = {}, c44 = {} is not a stable cubic crystal; it needs c44 > 0, "
        "c11 > c12 and c11 + 2 c12 > 0",
        style_, elasticity_.c11, elasticity_.c12, elasticity_.c44));
  }
}

config::MaterialKindSpec CubicJ2Plasticity::spec() {
  using config::Param;
  using units::Dimension;
  const auto modulus = [](const char* name, const char* doc, const ParameterRange& range) {
    return ranged(Param::real(name, Dimension::kPressure, doc).require().referable(), range);
  };
  return {std::string(kStyle),
          "MPM: von Mises plasticity on a cubic elastic crystal whose cube axes are x, y, z "
          "(cutting-plane return)",
          {density_param(),
           modulus("c11", "Cubic elastic constant C11, cube axes along x, y, z", kModulusRange),
           modulus("c12", "Cubic elastic constant C12", kAnyFiniteRange),
           modulus("c44", "Cubic elastic constant C44", kModulusRange),
           modulus("yield_stress", "Initial yield stress", kYieldStressRange),
           ranged(Param::real("hardening_modulus", Dimension::kPressure,
                              "Linear isotropic hardening modulus H")
                      .def(0.0)
                      .referable(),
                  kHardeningModulusRange)}};
}

std::unique_ptr<grid::Material> CubicJ2Plasticity::create(const MaterialParameters& params) {
  ParameterReader reader(kStyle, params);
  CubicElasticity c;
  c.c11 = reader.required("c11", kModulusRange);
  c.c12 = reader.required("c12", kAnyFiniteRange);
  c.c44 = reader.required("c44", kModulusRange);
  const double sy = reader.required("yield_stress", kYieldStressRange);
  const double h = reader.optional("hardening_modulus", 0.0, kHardeningModulusRange);
  reader.reject_unknown();
  return std::make_unique<CubicJ2Plasticity>(c, sy, h);
}

void CubicJ2Plasticity::update(const grid::Mat3& velocity_gradient, double dt,
                               grid::MaterialPointState& state) const {
  const grid::SymmetricTensor strain_increment = dt * rate_of_deformation(velocity_gradient);
  state.stress = rotated(state.stress, hughes_winget_rotation(velocity_gradient, dt)) +
                 elasticity_.stress_for(strain_increment);
  if (von_mises_stress(state.stress) > flow_stress(state.plastic_strain)) {
    return_to_yield_surface(state.stress, state.plastic_strain);
  }
}

// Each pass linearises the yield function f = q - flow_stress at the current
// stress: with flow direction n = 3 s / (2 q) (so that the equivalent
// plastic strain grows by the multiplier itself), the multiplier that zeroes
// the linearised f is f / (n : C : n + H). C : n is deviatoric for a cubic
// C, so the pressure stays elastic, as plastic flow is isochoric.
void CubicJ2Plasticity::return_to_yield_surface(grid::SymmetricTensor& stress,
                                                double& plastic_strain) const {
  for (int pass = 0; pass < kMaxReturnIterations; ++pass) {
    const grid::SymmetricTensor s = deviator(stress);
    const double q = std::sqrt(1.5 * double_contraction(s, s));
    const double f = q - flow_stress(plastic_strain);
    if (f <= kReturnTolerance * flow_stress(plastic_strain)) return;
    const grid::SymmetricTensor n = (1.5 / q) * s;
    const grid::SymmetricTensor cn = elasticity_.stress_for(n);
    const double multiplier = f / (double_contraction(n, cn) + hardening_.hardening_modulus);
    stress = stress + (-multiplier) * cn;
    plastic_strain += multiplier;
  }
  throw Error(fmt::format("{}: the return to the yield surface did not converge in {} passes",
                          style_, kMaxReturnIterations));
}

double CubicJ2Plasticity::wave_speed(const grid::MaterialPointState& state) const {
  return std::sqrt(elasticity_.max_longitudinal_modulus() / state.density);
}

double CubicJ2Plasticity::stored_energy_density(const grid::MaterialPointState& state) const {
  return elasticity_.strain_energy_density(state.stress);
}

double CubicJ2Plasticity::dissipated_energy_density(const grid::MaterialPointState& state) const {
  return hardening_.dissipated_energy_density(state.plastic_strain);
}

}  // namespace pbms::mpm
