#include "rod_tension_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "pbms/analysis/quasi_static_pull.hpp"
#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/mpi/sorted_rows.hpp"
#include "pbms/units.hpp"

namespace pbms::mpm {
namespace {

// The smallest gap between distinct coordinates of the rod's points along
// `axis` on any rank: the point spacing, so that a rod of n points spans
// n spacings, as a DPD rod of n planes spans n plane spacings.
double point_spacing(const MpmEngine& engine, std::uint32_t mask, std::size_t axis) {
  const grid::MaterialPoints& pts = engine.points();
  std::vector<double> c;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (pts.in_group(i, mask)) c.push_back(pts.x[i][axis]);
  }
  std::sort(c.begin(), c.end());
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < c.size(); ++k) {
    const double d = c[k] - c[k - 1];
    if (d > 1e-9 * std::max(1.0, std::abs(c[k]))) gap = std::min(gap, d);
  }
  double out = 0.0;
  mpi::check(MPI_Allreduce(&gap, &out, 1, MPI_DOUBLE, MPI_MIN, engine.comm()), "MPI_Allreduce");
  return std::isfinite(out) ? out : 0.0;
}

// The specimen's mass over its starting volume, over all ranks.
double mean_density(const MpmEngine& engine, std::uint32_t mask) {
  const grid::MaterialPoints& pts = engine.points();
  std::array<double, 2> mine{0.0, 0.0}, all{};
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!pts.in_group(i, mask)) continue;
    mine[0] += pts.mass[i];
    mine[1] += pts.volume0[i];
  }
  mpi::check(MPI_Allreduce(mine.data(), all.data(), 2, MPI_DOUBLE, MPI_SUM, engine.comm()),
             "MPI_Allreduce");
  return all[1] > 0.0 ? all[0] / all[1] : 0.0;
}

}  // namespace

RodTensionParams RodTensionParams::from_yaml(const YAML::Node& t) {
  RodTensionParams p;
  p.specimen = t["specimen"].as<std::string>();
  const auto a = t["axis"].as<std::string>();
  p.axis = a == "x" ? 0 : a == "y" ? 1 : 2;
  p.test = analysis::TensionTest::from_yaml(t);
  return p;
}

RodTensionAnalysis::RodTensionAnalysis(const RodTensionParams& t, const MpmEngine& engine,
                                       bool metal_units, const std::string& stage)
    : test_(t.test), mask_(engine.model().group_mask(t.specimen)), axis_(t.axis) {
  if (!metal_units) {
    throw Error(fmt::format("stage '{}': tension reports GPa and needs units: metal", stage));
  }
  for (std::size_t k = 0; k < 3; ++k) spacing_[k] = point_spacing(engine, mask_, k);
  const std::vector<double> m = measure(engine);
  length0_ = m[axis_];
  area0_ = 1.0;
  for (std::size_t k = 0; k < 3; ++k) {
    if (k == axis_) continue;
    area0_ *= m[k];
    width0_ = std::max(width0_, m[k]);
  }
  if (!(length0_ > 0.0 && area0_ > 0.0)) {
    throw Error(
        fmt::format("stage '{}': tension.specimen '{}' holds no extended rod", stage, t.specimen));
  }
  density_ = mean_density(engine, mask_);
  if (test_.gauge) find_gauge(engine);
}

void RodTensionAnalysis::find_gauge(const MpmEngine& engine) {
  const grid::MaterialPoints& pts = engine.points();
  std::vector<double> mine;  // id, axial coordinate
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (pts.in_group(i, mask_) && test_.gauge->half(pts.x[i][axis_]) >= 0) {
      mine.insert(mine.end(), {static_cast<double>(pts.id[i]), pts.x[i][axis_]});
    }
  }
  const std::vector<double> all = mpi::sorted_rows(engine.comm(), mine, 2, mpi::RowsTo::kEveryRank);
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) {
    gauge_start_.emplace(static_cast<std::int64_t>(all[k]), all[k + 1]);
  }
}

// The volume mean of the gauge points' axial Cauchy stress, and the
// distance of its halves' centroids (analysis::GaugeSection).
void RodTensionAnalysis::sample_gauge(const MpmEngine& engine) {
  const grid::MaterialPoints& pts = engine.points();
  const std::size_t a1 = (axis_ + 1) % 3, a2 = (axis_ + 2) % 3;
  analysis::GaugeSums g;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto it = gauge_start_.find(pts.id[i]);
    if (it == gauge_start_.end()) continue;
    g.add_stress(pts.state[i].stress.voigt[axis_] * pts.volume(i), pts.volume(i));
    g.add_member(test_.gauge->half(it->second), pts.x[i][axis_], {pts.x[i][a1], pts.x[i][a2]});
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, g.sums.data(), static_cast<int>(g.sums.size()), MPI_DOUBLE,
                           MPI_SUM, engine.comm()),
             "MPI_Allreduce");
  const double distance = g.centroid_distance();
  if (gauge_strain_.empty()) gauge_distance0_ = distance;
  gauge_strain_.push_back(distance / gauge_distance0_ - 1.0);
  gauge_stress_.push_back(g.sums[1] / g.sums[2] / units::kBarPerGPa);
}

std::vector<double> RodTensionAnalysis::measure(const MpmEngine& engine) const {
  const grid::MaterialPoints& pts = engine.points();
  const double inf = std::numeric_limits<double>::infinity();
  // Minima of x and of -x in one reduction.
  std::array<double, 6> lo{inf, inf, inf, inf, inf, inf};
  double work = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!pts.in_group(i, mask_)) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], pts.x[i][k]);
      lo[k + 3] = std::min(lo[k + 3], -pts.x[i][k]);
    }
    work += pts.state[i].stress.voigt[axis_] * pts.volume(i);
  }
  std::array<double, 6> glo{};
  double gwork = 0.0;
  mpi::check(MPI_Allreduce(lo.data(), glo.data(), 6, MPI_DOUBLE, MPI_MIN, engine.comm()),
             "MPI_Allreduce");
  mpi::check(MPI_Allreduce(&work, &gwork, 1, MPI_DOUBLE, MPI_SUM, engine.comm()), "MPI_Allreduce");
  std::vector<double> out(4);
  for (std::size_t k = 0; k < 3; ++k) out[k] = -glo[k + 3] - glo[k] + spacing_[k];
  out[3] = gwork;
  return out;
}

void RodTensionAnalysis::sample(const MpmEngine& engine, double t) {
  time_.push_back(t);
  const std::vector<double> m = measure(engine);
  const double length = m[axis_];
  strain_.push_back((length - length0_) / length0_);
  // The volume integral of the axial stress over the starting cross-section
  // times the current length: the measure of dpd_run's tension (its virial
  // over A0 L), so that both rods are judged alike.
  stress_.push_back(m[3] / (area0_ * length) / units::kBarPerGPa);
  if (test_.gauge) sample_gauge(engine);
}

void RodTensionAnalysis::report(StageResults& r, const std::string& stage) const {
  test_.report(r, strain_, stress_, stage);
  if (const auto fit_strain = r.scalar("fit_strain")) {
    analysis::check_quasi_static(r, density_, width0_,
                                 analysis::fit_window_time(strain_, time_, *fit_strain));
  }
  if (test_.gauge) test_.report_gauge(r, gauge_strain_, gauge_stress_, stage);
  r.attributes["cross_section_A2"] = fmt::format("{:.6g}", area0_);
}

void RodTensionAnalysis::save(CheckpointArchive& a) const {
  a.put("tension/measures",
        std::vector<double>{length0_, area0_, width0_, density_, gauge_distance0_});
  a.put("tension/time", time_);
  a.put("tension/strain", strain_);
  a.put("tension/stress", stress_);
  a.put("tension/gauge_strain", gauge_strain_);
  a.put("tension/gauge_stress", gauge_stress_);
}

void RodTensionAnalysis::load(const CheckpointArchive& a) {
  const auto& m = a.get("tension/measures");
  length0_ = m.at(0);
  area0_ = m.at(1);
  width0_ = m.at(2);
  density_ = m.at(3);
  gauge_distance0_ = m.at(4);
  time_ = a.get("tension/time");
  strain_ = a.get("tension/strain");
  stress_ = a.get("tension/stress");
  gauge_strain_ = a.get("tension/gauge_strain");
  gauge_stress_ = a.get("tension/gauge_stress");
}

}  // namespace pbms::mpm
