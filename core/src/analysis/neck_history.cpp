#include "pbms/analysis/neck_history.hpp"

namespace pbms::analysis {

void NeckHistory::add(double time_ps, const Neck& neck) {
  time_.push_back(time_ps);
  // Slabs a/2 thick cannot see a gap of a few ångström between rough
  // surfaces (a sphere's relaxed pole 6.6 Å from a rod fills every slab of
  // the gap): no neck until the bodies touch.
  width_.push_back(neck.closest <= touch_distance(a_) ? neck.width : 0.0);
  distance_.push_back(neck.centre_distance);
  closest_.push_back(neck.closest);
}

void NeckHistory::report(StageResults& r, double stable_time) const {
  if (time_.empty()) return;
  const std::string table = "neck_" + name_;
  r.add_column(table, "time", "ps", time_);
  r.add_column(table, "width", "Å", width_);
  r.add_column(table, "centre_distance", "Å", distance_);
  r.add_column(table, "closest", "Å", closest_);
  double sum = 0.0, n = 0.0;
  for (std::size_t k = 0; k < time_.size(); ++k) {
    if (time_[k] < time_.back() - stable_time - 1e-9) continue;
    sum += width_[k];
    n += 1.0;
  }
  r.add_scalar("neck_width_" + name_, sum / n, "Å");
  r.add_scalar("neck_final_" + name_, width_.back(), "Å");
  for (std::size_t k = 0; k < time_.size(); ++k) {
    if (closest_[k] <= touch_distance(a_)) {
      r.add_scalar("contact_time_" + name_, time_[k], "ps");
      break;
    }
  }
}

void NeckHistory::save(CheckpointArchive& a) const {
  a.put("neck_" + name_ + "/time", time_);
  a.put("neck_" + name_ + "/width", width_);
  a.put("neck_" + name_ + "/distance", distance_);
  a.put("neck_" + name_ + "/closest", closest_);
}

void NeckHistory::load(const CheckpointArchive& a) {
  time_ = a.get("neck_" + name_ + "/time");
  width_ = a.get("neck_" + name_ + "/width");
  distance_ = a.get("neck_" + name_ + "/distance");
  closest_ = a.get("neck_" + name_ + "/closest");
}

}  // namespace pbms::analysis
