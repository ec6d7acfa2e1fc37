// An mpm_run stage's run settings, read once from its checked parameters
// (the schema is MpmRunStage::spec(), in mpm_run_spec.cpp). Bodies, groups
// and conditions go to build_model, probes to ProbeSeries, the wave_front
// map to BarWaveAnalysis.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

namespace pbms::mpm {

struct MpmRunParams {
  bool metal_units = true;
  std::optional<double> time_step;  // empty: auto
  double courant = 0.5;
  double duration = 0.0;
  std::int64_t sample_every = 10;
  std::int64_t particles_every = 0;  // 0: no particle frames
  std::int64_t grid_every = 0;       // 0: no grid frames
  std::string gradient;
  std::string period_of;  // a probe column, or empty

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
