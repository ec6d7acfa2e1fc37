// A dpd_run or dpd_equilibrate stage's parameters, read once from its
// checked map (the schema is DpdRunStage::spec() and
// DpdEquilibrateStage::spec(), dpd_run_spec.cpp): the body and run settings
// every DPD stage takes, and the mode's own map.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "dpd_stage_params.hpp"
#include "pbms/analysis/tension_test.hpp"
#include "pbms/coupling/neck_spec.hpp"

namespace pbms::dpd {

// The slabs' histories of the same body run without the impact: the
// `slabs` table of an earlier dpd_run stage.
struct SlabBaseline {
  std::vector<double> time, near, far;  // ps, Å, Å

  static SlabBaseline from_yaml(const YAML::Node& table);
};

// mode: impact. The wave between two slabs.
struct ImpactParams {
  std::string near_slab, far_slab;
  int axis = 0;
  double threshold = 0.0;      // Å: a slab's first motion
  bool mid_amplitude = false;  // wave_speed times the mid-amplitude arrival, not first motion
  double smoothing = 0.0;      // ps
  double window = 0.0;         // ps
  std::optional<SlabBaseline> baseline;
  double pulse_lo = 0.0, pulse_hi = 0.0;  // Å: the ladder of levels of pulse_speed

  static ImpactParams from_yaml(const YAML::Node& impact);
};

// mode: tension. The rod's stress and strain, and what is reported of them.
struct TensionParams {
  std::string specimen;
  int axis = 0;
  std::optional<double> area;                                // Å²; empty: from the extents
  std::optional<std::pair<std::string, std::string>> grips;  // left, right
  analysis::TensionTest test;

  static TensionParams from_yaml(const YAML::Node& tension);
};

struct DpdRunParams {
  enum class Mode { kFree, kImpact, kTension, kEquilibrate };
  Mode mode = Mode::kFree;
  DpdStageParams stage;
  std::optional<ImpactParams> impact;
  std::optional<TensionParams> tension;
  double target_temperature = 0.0;  // dpd_equilibrate's Berendsen thermostat
  double tau = 0.0;                 // ps
  std::vector<coupling::NeckPair> necks;
  double neck_stable_time = 20.0;  // ps
  // The stage whose noise stream (and drawn velocities) this one takes:
  // a baseline run and the run it is subtracted from share their noise.
  std::optional<std::string> noise_of;

  // dpd_run's map, with its mode.
  static DpdRunParams from_yaml(const YAML::Node& params);
  // dpd_equilibrate's map.
  static DpdRunParams equilibrate_from_yaml(const YAML::Node& params);
};

}  // namespace pbms::dpd
