// The tension analysis of a dpd_run stage (mode tension, seed §5.2.2): the
// specimen's strain (its length along the axis, outermost sites plus a
// lattice plane) and its mean conservative virial stress every sample, the
// grips' pull on the rod and, with a gauge, the middle section's own
// reading; at the end, analysis::TensionTest's modulus and yield.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dpd_gauge.hpp"
#include "dpd_model.hpp"
#include "dpd_run_params.hpp"
#include "engine/dpd_engine.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::dpd {

class DpdTensionAnalysis {
 public:
  // Before the engine takes the model's particles: the gauge's members
  // come from the full starting set.
  DpdTensionAnalysis(const TensionParams& params, const DpdModel& model,
                     const MesoparticleMaterial& material);

  // Collective, once the engine holds the particles: the specimen's
  // starting length, cross-section and width.
  void start(const DpdEngine& engine);
  // Collective: one sample at time `t` (ps), with the step's conservative
  // virial.
  void sample(const DpdEngine& engine, const ThermoState& thermo, double t);
  // Rank 0 at the end.
  void report(StageResults& r, const std::string& stage) const;
  // Its samples and starting measures, for a checkpoint; and back.
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  TensionParams params_;
  double plane_;    // half the lattice constant: a (100) plane spacing
  double density_;  // g/mol/Å^3 of the fcc crystal the rod is cut from
  std::uint32_t specimen_ = 0, left_grip_ = 0, right_grip_ = 0;
  std::unique_ptr<DpdGauge> gauge_;
  double area_ = 0.0, length0_ = 0.0;
  double site_volume_ = 0.0;  // the specimen's sites times a³/4, Å^3
  double width_ = 0.0;        // the widest lateral extent, Å
  std::vector<double> time_, strain_, stress_, grip_stress_;
};

}  // namespace pbms::dpd
