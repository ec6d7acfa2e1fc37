// The impact analysis of a dpd_run stage (mode impact, seed §5.2.1): the
// centre-of-mass displacement of two slabs along the wave's axis every
// step, and from their arrival times the wave speed between them. With a
// baseline (the same body from the same start with the same noise, not
// struck) the speeds are timed on the difference, the slabs' response to
// the impact alone.
#pragma once

#include <cstdint>
#include <vector>

#include "dpd_model.hpp"
#include "dpd_run_params.hpp"
#include "engine/dpd_engine.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::dpd {

class DpdImpactAnalysis {
 public:
  // Collective: the slabs' starting centres of mass.
  DpdImpactAnalysis(const ImpactParams& params, const DpdModel& model, const DpdEngine& engine);

  // Collective: the slabs' displacements after `step`.
  void track(const DpdEngine& engine, std::int64_t step, double dt);
  // Rank 0 at the end: arrival times, speeds and front velocities; where
  // the wave did not reach both slabs, the histories, and why there is no
  // speed.
  void report(StageResults& r) const;
  // The slabs' histories, for a checkpoint; and back.
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  // The speeds from one pair of histories: the slabs' own or, with a
  // baseline, their responses.
  void report_arrivals(StageResults& r, const std::vector<double>& near,
                       const std::vector<double>& far) const;
  void report_pulse(StageResults& r, const std::vector<double>& near,
                    const std::vector<double>& far, double distance) const;
  static std::vector<double> less_baseline(const std::vector<double>& mine,
                                           const std::vector<double>& base);

  ImpactParams params_;
  std::uint32_t near_mask_ = 0, far_mask_ = 0;
  Vec3 near0_{}, far0_{};
  std::vector<double> time_, near_, far_;
};

}  // namespace pbms::dpd
