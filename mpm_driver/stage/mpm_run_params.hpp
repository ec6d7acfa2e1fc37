// An mpm_run stage's parameters, read once from its checked map (the schema
// is MpmRunStage::spec(), in mpm_run_spec.cpp): the run settings here, the
// model for build_model, the probes for ProbeSeries, the wave_front map for
// BarWaveAnalysis and the tension map for RodTensionAnalysis.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "bar_wave_analysis.hpp"
#include "mpm_model_params.hpp"
#include "mpm_probes.hpp"
#include "rod_tension_analysis.hpp"

namespace pbms::mpm {

struct MpmRunParams {
  MpmModelParams model;
  bool metal_units = true;
  std::optional<double> time_step;  // empty: auto
  double courant = 0.5;
  double duration = 0.0;
  std::int64_t sample_every = 10;
  std::int64_t particles_every = 0;  // 0: no particle frames
  std::int64_t grid_every = 0;       // 0: no grid frames
  std::string gradient;
  std::string period_of;  // a probe column, or empty
  std::vector<ProbeSpec> probes;
  std::optional<WaveFrontParams> wave_front;
  std::optional<RodTensionParams> tension;

  static MpmRunParams from_yaml(const YAML::Node& params);

  // The step to take under a CFL bound h / max(c + |v|): courant times it
  // for `auto`; an explicit step above it is refused (pbms::Error naming
  // the stage).
  [[nodiscard]] double time_step_for(double cfl_bound, double cell_size,
                                     const std::string& stage) const;
  // Steps that cover the duration at dt.
  [[nodiscard]] std::int64_t steps(double dt) const;
  [[nodiscard]] std::string time_unit() const { return metal_units ? "ps" : "1"; }
};

}  // namespace pbms::mpm
