// The analysis part of a tension stage (dpd_run mode tension, mpm_run's
// `tension` map): its keys, declared once for both programs' specs, read
// once into this struct, and the results it reports from the sampled
// stress-strain curve. The stress measure itself is each program's own.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/analysis/gauge_section.hpp"
#include "pbms/analysis/tension_curve.hpp"
#include "pbms/config/param.hpp"
#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/results.hpp"

namespace pbms::analysis {

struct TensionTest {
  std::optional<double> fit_strain;  // empty: up to the stress maximum
  YieldRule yield;
  std::optional<GaugeSection> gauge;  // the tension map's `gauge`, if given

  // The keys inside a stage's tension map that this analysis owns.
  static std::vector<config::Param> params();
  // youngs_modulus, max_stress, fit_strain, yield_stress, yield_strain and
  // the tension_curve table; `what` names the mode in their docs.
  static std::vector<config::OutputSpec> outputs(const std::string& what);
  // From a checked tension map.
  static TensionTest from_yaml(const YAML::Node& tension);

  // Rank 0 of a finished run: strain (1) and stress (GPa), one sample each.
  // Throws pbms::Error naming the stage with fewer than 3 samples to fit.
  void report(StageResults& r, const std::vector<double>& strain, const std::vector<double>& stress,
              const std::string& stage) const;
  // The grips' measure beside the mean stress: grip_youngs_modulus, the
  // slope of the grips' stress (their holding force over the initial
  // cross-section, GPa) against the same strain over the same window as
  // youngs_modulus, and the tension_curve's grip_stress column. After
  // report, with its strain and stress. Throws as report.
  void report_grips(StageResults& r, const std::vector<double>& strain,
                    const std::vector<double>& stress, const std::vector<double>& grip_stress,
                    const std::string& stage) const;
  // The gauge's outputs (gauge_*) from its strain (1) and Cauchy stress
  // (GPa) samples. The modulus is fitted up to the gauge's
  // fit_stress_fraction of its largest smoothed stress. The yield point is
  // the first load drop or, on a curve that levels off without one (a J2
  // rod without hardening: within a drop's size of its maximum for the
  // last tenth of its strain range), the largest smoothed stress. Throws
  // as report.
  void report_gauge(StageResults& r, const std::vector<double>& strain,
                    const std::vector<double>& stress, const std::string& stage) const;

 private:
  // The fit's upper strain: fit_strain, or the strain at the stress maximum.
  [[nodiscard]] double fit_end(const std::vector<double>& strain,
                               const std::vector<double>& stress) const;
};

}  // namespace pbms::analysis
