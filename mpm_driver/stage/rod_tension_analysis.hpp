// The tension analysis of an mpm_run (seed §5.2.2 on a continuum rod): the
// rod's mean axial stress and its strain sampled through the run, then
// Young's modulus and the yield point by the rules dpd_run's tension uses
// (analysis::TensionTest), so that an MPM rod calibrated from a DPD rod can
// be held against it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "engine/mpm_engine.hpp"
#include "pbms/analysis/tension_test.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::mpm {

// The stage's tension map: the rod, its axis and the analysis' own keys.
struct RodTensionParams {
  std::string specimen;
  std::size_t axis = 0;
  analysis::TensionTest test;

  static RodTensionParams from_yaml(const YAML::Node& tension);
};

class RodTensionAnalysis {
 public:
  // Collective: measures the rod's starting length and cross-section.
  // Throws pbms::Error naming the stage unless the run is in metal units.
  RodTensionAnalysis(const RodTensionParams& tension, const MpmEngine& engine, bool metal_units,
                     const std::string& stage);

  // Collective: one sample of strain and stress at time `t`.
  void sample(const MpmEngine& engine, double t);
  // The results of analysis::TensionTest, and the cross-section (the same on
  // every rank).
  void report(StageResults& r, const std::string& stage) const;
  // Its samples and starting measures, for a checkpoint; and back.
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  // The rod's extents along x, y, z, each plus the point spacing along it,
  // over all ranks; the sum of sigma_aa V as the fourth entry.
  [[nodiscard]] std::vector<double> measure(const MpmEngine& engine) const;

  // The gauge's members by id: their starting axial coordinate.
  void find_gauge(const MpmEngine& engine);
  void sample_gauge(const MpmEngine& engine);

  analysis::TensionTest test_;
  std::uint32_t mask_ = 0;
  std::size_t axis_ = 0;
  std::array<double, 3> spacing_{};
  double length0_ = 0.0, area0_ = 0.0, width0_ = 0.0;
  double density_ = 0.0;  // the specimen's mass over its starting volume
  std::vector<double> time_, strain_, stress_;
  std::unordered_map<std::int64_t, double> gauge_start_;
  double gauge_distance0_ = 0.0;
  std::vector<double> gauge_strain_, gauge_stress_;
};

}  // namespace pbms::mpm
