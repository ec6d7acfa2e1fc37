// The wave_front analysis of an mpm_run (the seed's Appendix-2 bar): the
// front of a step-loaded bar tracked through the run, and at set times the
// plateau stress behind it and the whole stress profile, compared with the
// exact d'Alembert solution (StepLoadedBar).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "engine/mpm_engine.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"
#include "wave_front.hpp"

namespace pbms::mpm {

// The stage's wave_front map.
struct WaveFrontParams {
  std::string group;  // the bar
  double loaded_end = 0.0;
  double fixed_end = 0.0;
  double traction = 0.0;
  double profile_time = 0.0;
  std::optional<double> rms_reference;        // a plain MPM run's rms_from_exact
  std::optional<double> variation_reference;  // a plain MPM run's excess_variation

  static WaveFrontParams from_yaml(const YAML::Node& wave_front);
};

class BarWaveAnalysis {
 public:
  // The run takes `steps` of `dt`. Throws pbms::Error if the profile time
  // is after the run.
  BarWaveAnalysis(const WaveFrontParams& wave_front, const MpmEngine& engine, double dt,
                  std::int64_t steps, const std::string& stage);

  // The front's position, while it is between 0.1 and 0.9 of its transit.
  void sample(const MpmEngine& engine, double t);
  // The plateau stress and the profile, at the steps they are due.
  void after_step(const MpmEngine& engine, std::int64_t step, double t);
  // Rank 0: the scalars and the front and profile tables.
  void report(StageResults& r, bool metal_units, const std::string& stage) const;
  // What it has measured so far, for a checkpoint; and back.
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  // The bar's points as rows (id, x, sigma_xx, volume) in id order on rank 0.
  [[nodiscard]] std::vector<double> profile_rows(const MpmEngine& engine) const;

  StepLoadedBar bar_;
  std::uint32_t mask_ = 0;
  std::optional<double> rms_reference_, variation_reference_;
  std::int64_t steps_ = 0, plateau_step_ = -1, profile_step_ = -1;
  std::vector<double> front_t_, front_s_, profile_;
  double plateau_ = NAN, rms_ = NAN, variation_ = NAN, profile_t_ = -1.0;
};

}  // namespace pbms::mpm
