// A neck's width over a run, and what a stage reports of it: the table
// neck_<name> (time, width: 0 until the bodies touch, centre distance,
// closest approach) and the
// scalars neck_width_<name> (the mean over the run's last `stable_time`:
// the stable neck), neck_final_<name> and contact_time_<name> (the first
// sample where the bodies touch, by touch_distance(a); absent if never). Shared by the DPD part's
// probe and md_driver, so that both report a neck under the same names.
#pragma once

#include <string>
#include <vector>

#include "pbms/analysis/neck_width.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::analysis {

class NeckHistory {
 public:
  // `a`: the bodies' lattice constant.
  NeckHistory(std::string name, double a) : name_(std::move(name)), a_(a) {}

  void add(double time_ps, const Neck& neck);
  void report(StageResults& r, double stable_time) const;
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  std::string name_;
  double a_;
  std::vector<double> time_, width_, distance_, closest_;
};

}  // namespace pbms::analysis
