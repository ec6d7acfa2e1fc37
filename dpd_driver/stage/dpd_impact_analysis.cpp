#include "dpd_impact_analysis.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "dpd_probes.hpp"
#include "pbms/analysis/first_crossing.hpp"
#include "pbms/analysis/front_arrival.hpp"
#include "pbms/analysis/level_delays.hpp"

namespace pbms::dpd {
namespace {

// Å/ps is 100 m/s.
constexpr double kMetresPerSecond = 100.0;
constexpr std::size_t kPulseLevels = 8;

}  // namespace

DpdImpactAnalysis::DpdImpactAnalysis(const ImpactParams& params, const DpdModel& model,
                                     const DpdEngine& engine)
    : params_(params),
      near_mask_(model.group_mask(params.near_slab)),
      far_mask_(model.group_mask(params.far_slab)) {
  near0_ = DpdProbes::centre_of_mass(engine, near_mask_);
  far0_ = DpdProbes::centre_of_mass(engine, far_mask_);
}

void DpdImpactAnalysis::track(const DpdEngine& engine, std::int64_t step, double dt) {
  const int axis = params_.axis;
  const Vec3 a = DpdProbes::centre_of_mass(engine, near_mask_);
  const Vec3 b = DpdProbes::centre_of_mass(engine, far_mask_);
  time_.push_back(static_cast<double>(step) * dt);
  near_.push_back(a[axis] - near0_[axis]);
  far_.push_back(b[axis] - far0_[axis]);
}

std::vector<double> DpdImpactAnalysis::less_baseline(const std::vector<double>& mine,
                                                     const std::vector<double>& base) {
  std::vector<double> out(mine.size());
  for (std::size_t k = 0; k < mine.size(); ++k) out[k] = mine[k] - base.at(k);
  return out;
}

void DpdImpactAnalysis::report(StageResults& r) const {
  r.add_column("slabs", "time", "ps", time_);
  r.add_column("slabs", "near_displacement", "Å", near_);
  r.add_column("slabs", "far_displacement", "Å", far_);
  if (params_.baseline) {
    const std::vector<double> near = less_baseline(near_, params_.baseline->near);
    const std::vector<double> far = less_baseline(far_, params_.baseline->far);
    r.add_column("slabs", "near_response", "Å", near);
    r.add_column("slabs", "far_response", "Å", far);
    report_arrivals(r, near, far);
  } else {
    report_arrivals(r, near_, far_);
  }
}

void DpdImpactAnalysis::report_arrivals(StageResults& r, const std::vector<double>& near_history,
                                        const std::vector<double>& far_history) const {
  const double distance = std::abs(far0_[params_.axis] - near0_[params_.axis]);
  const double t_near = analysis::first_crossing(time_, near_history, params_.threshold);
  const double t_far = analysis::first_crossing(time_, far_history, params_.threshold);
  report_pulse(r, near_history, far_history, distance);
  if (params_.baseline && !std::isnan(t_near)) {
    double residual = 0.0;
    for (std::size_t k = 0; k < time_.size() && time_[k] < t_near; ++k) {
      residual = std::max(residual, std::abs(far_history[k]));
    }
    r.add_scalar("baseline_residual", residual, "Å");
  }
  if (!(t_far > t_near)) {
    r.attributes["wave_speed"] = fmt::format(
        "not measured: the wave did not reach both slabs (first motion near {:.4g} ps, far "
        "{:.4g} ps); run longer or lower impact.threshold",
        t_near, t_far);
    return;
  }
  const double first_motion_speed = distance / (t_far - t_near) * kMetresPerSecond;
  r.add_scalar("first_motion_near", t_near, "ps");
  r.add_scalar("first_motion_far", t_far, "ps");
  r.add_scalar("first_motion_speed", first_motion_speed, "m/s");
  const analysis::FrontArrival near = analysis::mid_amplitude_arrival(
      time_, near_history, t_near, params_.smoothing, params_.window);
  const analysis::FrontArrival far =
      analysis::mid_amplitude_arrival(time_, far_history, t_far, params_.smoothing, params_.window);
  if (far.time > near.time) {
    const double speed = distance / (far.time - near.time) * kMetresPerSecond;
    r.add_scalar("mid_amplitude_speed", speed, "m/s");
    r.add_scalar("front_near", near.time, "ps");
    r.add_scalar("front_far", far.time, "ps");
    r.add_scalar("front_velocity_near", near.amplitude * kMetresPerSecond, "m/s");
    r.add_scalar("front_velocity_far", far.amplitude * kMetresPerSecond, "m/s");
    r.add_scalar("particle_velocity", 0.5 * (near.amplitude + far.amplitude) * kMetresPerSecond,
                 "m/s");
    if (params_.mid_amplitude) r.add_scalar("wave_speed", speed, "m/s");
  } else if (params_.mid_amplitude) {
    r.attributes["wave_speed"] = fmt::format(
        "not measured: no mid-amplitude arrival at both slabs (near {:.4g} ps, far {:.4g} ps)",
        near.time, far.time);
  }
  if (!params_.mid_amplitude) r.add_scalar("wave_speed", first_motion_speed, "m/s");
}

void DpdImpactAnalysis::report_pulse(StageResults& r, const std::vector<double>& near,
                                     const std::vector<double>& far, double distance) const {
  const analysis::LevelDelays d =
      analysis::level_delays(time_, near, far, params_.pulse_lo, params_.pulse_hi, kPulseLevels);
  if (d.mean() > 0.0) {
    r.add_scalar("pulse_speed", distance / d.mean() * kMetresPerSecond, "m/s");
    std::vector<double> speeds;
    for (const double delay : d.delays) speeds.push_back(distance / delay * kMetresPerSecond);
    r.add_column("pulse", "level", "Å", d.levels);
    r.add_column("pulse", "delay", "ps", d.delays);
    r.add_column("pulse", "speed", "m/s", speeds);
  } else {
    r.attributes["pulse_speed"] =
        fmt::format("not measured: the slabs do not both reach every level from {:.4g} to {:.4g} Å",
                    params_.pulse_lo, params_.pulse_hi);
  }
}

void DpdImpactAnalysis::save(CheckpointArchive& a) const {
  a.put("impact/start",
        std::vector<double>{near0_[0], near0_[1], near0_[2], far0_[0], far0_[1], far0_[2]});
  a.put("impact/time", time_);
  a.put("impact/near", near_);
  a.put("impact/far", far_);
}

void DpdImpactAnalysis::load(const CheckpointArchive& a) {
  const auto& s = a.get("impact/start");
  near0_ = {s.at(0), s.at(1), s.at(2)};
  far0_ = {s.at(3), s.at(4), s.at(5)};
  time_ = a.get("impact/time");
  near_ = a.get("impact/near");
  far_ = a.get("impact/far");
}

}  // namespace pbms::dpd
