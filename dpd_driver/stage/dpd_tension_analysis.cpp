#include "dpd_tension_analysis.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "dpd_probes.hpp"
#include "pbms/analysis/quasi_static_pull.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

DpdTensionAnalysis::DpdTensionAnalysis(const TensionParams& params, const DpdModel& model,
                                       const MesoparticleMaterial& material)
    : params_(params),
      plane_(0.5 * material.lattice_constant),
      density_(4.0 * material.mass / std::pow(material.lattice_constant, 3)) {
  if (params.test.gauge) {
    gauge_ = std::make_unique<DpdGauge>(*params.test.gauge, model.particles,
                                        model.group_mask(params.specimen), params.axis, plane_);
  }
  specimen_ = model.group_mask(params.specimen);
  double sites = 0.0;
  for (std::size_t i = 0; i < model.particles.size(); ++i) {
    if ((model.particles.group_mask[i] & specimen_) != 0) sites += 1.0;
  }
  site_volume_ = sites * std::pow(material.lattice_constant, 3) / 4.0;
  if (params.grips) {
    left_grip_ = model.group_mask(params.grips->first);
    right_grip_ = model.group_mask(params.grips->second);
  }
}

void DpdTensionAnalysis::start(const DpdEngine& engine) {
  // An fcc crystal of n cells spans n a; its outermost sites, n a − a/2.
  length0_ = DpdProbes::extent(engine, specimen_, params_.axis) + plane_;
  for (int a = 0; a < 3; ++a) {
    if (a != params_.axis) {
      width_ = std::max(width_, DpdProbes::extent(engine, specimen_, a) + plane_);
    }
  }
  // The nominal cross-section, the sites' volume over the length, as
  // md_tension's ny a x nz a: at 298 K the outermost sites' excursions
  // widen the lateral extents by about 0.8 Å, 2 % of a 10 x 10 a_cg rod's
  // area and 4 % of a 6 x 6 one's (docs/concurrent.md).
  area_ = params_.area ? *params_.area : site_volume_ / length0_;
  if (gauge_) gauge_->set_starting_area(area_);
}

void DpdTensionAnalysis::sample(const DpdEngine& engine, const ThermoState& thermo, double t) {
  const int axis = params_.axis;
  time_.push_back(t);
  const double length = DpdProbes::extent(engine, specimen_, axis) + plane_;
  strain_.push_back((length - length0_) / length0_);
  // Tension positive: σ = −W / V, eV/Å^3 to GPa.
  stress_.push_back(-thermo.virial[static_cast<std::size_t>(axis)] / (area_ * length) *
                    units::kBarPerEvPerA3 / units::kBarPerGPa);
  if (gauge_) gauge_->sample(engine);
  if (left_grip_ != 0) {
    const auto a = static_cast<std::size_t>(axis);
    const double pull = 0.5 * (DpdProbes::group_force(engine, left_grip_)[a] -
                               DpdProbes::group_force(engine, right_grip_)[a]);
    grip_stress_.push_back(pull / area_ * units::kBarPerEvPerA3 / units::kBarPerGPa);
  }
}

void DpdTensionAnalysis::report(StageResults& r, const std::string& stage) const {
  params_.test.report(r, strain_, stress_, stage);
  if (const auto fit_strain = r.scalar("fit_strain")) {
    analysis::check_quasi_static(r, density_, width_,
                                 analysis::fit_window_time(strain_, time_, *fit_strain));
  }
  if (left_grip_ != 0) params_.test.report_grips(r, strain_, stress_, grip_stress_, stage);
  if (gauge_) gauge_->report(params_.test, r, stage);
  r.attributes["cross_section_A2"] = fmt::format("{:.6g}", area_);
}

void DpdTensionAnalysis::save(CheckpointArchive& a) const {
  a.put("tension/measures", std::vector<double>{area_, length0_, width_});
  a.put("tension/time", time_);
  a.put("tension/strain", strain_);
  a.put("tension/stress", stress_);
  a.put("tension/grip_stress", grip_stress_);
  if (gauge_) gauge_->save(a);
}

void DpdTensionAnalysis::load(const CheckpointArchive& a) {
  const auto& m = a.get("tension/measures");
  area_ = m.at(0);
  length0_ = m.at(1);
  width_ = m.at(2);
  time_ = a.get("tension/time");
  strain_ = a.get("tension/strain");
  stress_ = a.get("tension/stress");
  grip_stress_ = a.get("tension/grip_stress");
  if (gauge_) gauge_->load(a);
}

}  // namespace pbms::dpd
