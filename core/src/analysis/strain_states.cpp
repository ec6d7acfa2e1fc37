#include "pbms/analysis/strain_states.hpp"

#include <cmath>
#include <cstddef>

#include "pbms/error.hpp"

namespace pbms::analysis {

std::string strain_state_name(StrainState state) {
  switch (state) {
    case StrainState::kTetragonalPlus:
      return "tetragonal_plus";
    case StrainState::kTetragonalMinus:
      return "tetragonal_minus";
    case StrainState::kShearPlus:
      return "shear_plus";
    case StrainState::kShearMinus:
      return "shear_minus";
  }
  return "unknown";
}

StrainState strain_state_from_name(const std::string& name) {
  for (const StrainState s : kStrainStates) {
    if (strain_state_name(s) == name) return s;
  }
  throw Error("DPD elastic constants: no strain state '" + name +
              "' (tetragonal_plus, tetragonal_minus, shear_plus, shear_minus)");
}

std::array<double, 3> strain_of(StrainState state, double strain) {
  switch (state) {
    case StrainState::kTetragonalPlus:
      return {0.0, 0.0, strain};
    case StrainState::kTetragonalMinus:
      return {0.0, 0.0, -strain};
    case StrainState::kShearPlus:
      return {strain, -strain, 0.0};
    case StrainState::kShearMinus:
      return {-strain, strain, 0.0};
  }
  return {0.0, 0.0, 0.0};
}

std::vector<CauchyStress> stress_block_means(const std::vector<CauchyStress>& samples) {
  std::array<std::vector<double>, 6> means;
  std::vector<double> component(samples.size());
  for (int c = 0; c < 6; ++c) {
    for (std::size_t k = 0; k < samples.size(); ++k) component[k] = samples[k][c];
    means[c] = block_means(component, kStateBlocks);
    if (means[c].empty()) means[c] = {average_of_blocks(component).mean};
  }
  std::vector<CauchyStress> blocks(means[0].size());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    for (int c = 0; c < 6; ++c) blocks[b][c] = means[c][b];
  }
  return blocks;
}

ElasticConstants elastic_constants_from_states(
    const std::array<std::vector<CauchyStress>, 4>& block_means, double strain) {
  if (!(strain > 0.0)) throw Error("DPD elastic constants: the strain must be > 0");
  const std::size_t n = block_means[0].size();
  for (const auto& state : block_means) {
    if (state.size() != n || n == 0) {
      throw Error(
          "DPD elastic constants: the strained states have different numbers of blocks (sampled "
          "with different settings)");
    }
  }
  const auto& tetragonal_plus = block_means[0];
  const auto& tetragonal_minus = block_means[1];
  const auto& shear_plus = block_means[2];
  const auto& shear_minus = block_means[3];
  const double over = 1.0 / (2.0 * strain);
  std::vector<double> c11(n), c12(n), c44(n), youngs(n), bulk(n), p(n);
  for (std::size_t b = 0; b < n; ++b) {
    const auto d = [&](const std::vector<CauchyStress>& plus,
                       const std::vector<CauchyStress>& minus,
                       int c) { return plus[b][c] - minus[b][c]; };
    c11[b] = d(tetragonal_plus, tetragonal_minus, 2) * over;
    c12[b] = 0.5 *
             (d(tetragonal_plus, tetragonal_minus, 0) + d(tetragonal_plus, tetragonal_minus, 1)) *
             over;
    c44[b] = 0.25 * (d(shear_plus, shear_minus, 0) - d(shear_plus, shear_minus, 1)) * over;
    p[b] = 0.5 * (pressure_of(tetragonal_plus[b]) + pressure_of(tetragonal_minus[b]));
    const CubicModuli block{c11[b], c12[b], c44[b]};
    youngs[b] = block.youngs_modulus_100();
    bulk[b] = block.bulk_modulus();
  }
  ElasticConstants result;
  const BlockAverage c11_estimate = average_of_blocks(c11);
  const BlockAverage c12_estimate = average_of_blocks(c12);
  const BlockAverage c44_estimate = average_of_blocks(c44);
  const BlockAverage pressure = average_of_blocks(p);
  result.c11 = c11_estimate.mean;
  result.c12 = c12_estimate.mean;
  result.c44 = c44_estimate.mean;
  result.c11_error = c11_estimate.error;
  result.c12_error = c12_estimate.error;
  result.c44_error = c44_estimate.error;
  result.youngs_100_error = average_of_blocks(youngs).error;
  result.bulk_modulus_error = average_of_blocks(bulk).error;
  result.pressure = pressure.mean;
  result.pressure_error = pressure.error;
  return result;
}

}  // namespace pbms::analysis
