#include "bar_wave_analysis.hpp"

#include <cmath>

#include <fmt/format.h>

#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/mpi/sorted_rows.hpp"

namespace pbms::mpm {
namespace {

double allreduce_max(MPI_Comm comm, double v) {
  double out = 0.0;
  mpi::check(MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MAX, comm), "MPI_Allreduce");
  return out;
}

// Column `c` of rows of four.
std::vector<double> column(const std::vector<double>& rows, std::size_t c) {
  std::vector<double> out;
  for (std::size_t r = 0; r + 4 <= rows.size(); r += 4) out.push_back(rows[r + c]);
  return out;
}

}  // namespace

WaveFrontParams WaveFrontParams::from_yaml(const YAML::Node& wf) {
  WaveFrontParams p;
  p.group = wf["group"].as<std::string>();
  p.loaded_end = wf["loaded_end"].as<double>();
  p.fixed_end = wf["fixed_end"].as<double>();
  p.traction = wf["traction"].as<double>();
  p.profile_time = wf["profile_time"].as<double>();
  if (wf["rms_reference"]) p.rms_reference = wf["rms_reference"].as<double>();
  if (wf["variation_reference"]) p.variation_reference = wf["variation_reference"].as<double>();
  return p;
}

BarWaveAnalysis::BarWaveAnalysis(const WaveFrontParams& wf, const MpmEngine& engine, double dt,
                                 std::int64_t steps, const std::string& stage)
    : mask_(engine.model().group_mask(wf.group)),
      rms_reference_(wf.rms_reference),
      variation_reference_(wf.variation_reference),
      steps_(steps) {
  bar_.loaded_end = wf.loaded_end;
  bar_.fixed_end = wf.fixed_end;
  bar_.traction = wf.traction;
  const grid::MaterialPoints& pts = engine.points();
  const auto& units = engine.model().options.units;
  double c = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!pts.in_group(i, mask_)) continue;
    c = engine.solver().material(pts.material[i]).wave_speed(pts.state[i]) *
        std::sqrt(units.stress_volume_to_energy * units.force_per_mass_to_accel);
    break;
  }
  bar_.wave_speed = allreduce_max(engine.comm(), c);
  plateau_step_ = std::llround(0.8 * bar_.transit_time() / dt);
  profile_step_ = std::llround(wf.profile_time / dt);
  if (profile_step_ > steps) {
    throw Error(
        fmt::format("stage '{}': wave_front.profile_time is after the end of the run", stage));
  }
}

std::vector<double> BarWaveAnalysis::profile_rows(const MpmEngine& engine) const {
  const grid::MaterialPoints& pts = engine.points();
  std::vector<double> rows;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!pts.in_group(i, mask_)) continue;
    rows.insert(rows.end(), {static_cast<double>(pts.id[i]), pts.x[i][0],
                             pts.state[i].stress.voigt[0], pts.volume(i)});
  }
  return mpi::sorted_rows(engine.comm(), rows, 4, mpi::RowsTo::kRankZero);
}

void BarWaveAnalysis::sample(const MpmEngine& engine, double t) {
  if (!(t > 0.1 * bar_.transit_time() && t < 0.9 * bar_.transit_time())) return;
  const grid::MaterialPoints& pts = engine.points();
  std::vector<double> x, sxx;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!pts.in_group(i, mask_)) continue;
    x.push_back(pts.x[i][0]);
    sxx.push_back(pts.state[i].stress.voigt[0]);
  }
  front_t_.push_back(t);
  front_s_.push_back(allreduce_max(engine.comm(), front_distance(bar_, x, sxx)));
}

void BarWaveAnalysis::after_step(const MpmEngine& engine, std::int64_t step, double t) {
  if (step == plateau_step_) {
    const auto rows = profile_rows(engine);
    if (engine.rank() == 0)
      plateau_ = plateau_stress(bar_, t, column(rows, 1), column(rows, 2), column(rows, 3));
  }
  if (step == profile_step_) {
    profile_ = profile_rows(engine);
    profile_t_ = t;
    if (engine.rank() == 0) {
      rms_ = rms_from_exact(bar_, t, column(profile_, 1), column(profile_, 2));
      variation_ = excess_variation(bar_, t, column(profile_, 1), column(profile_, 2));
    }
  }
}

void BarWaveAnalysis::report(StageResults& r, bool metal, const std::string& stage) const {
  const std::string stress_unit = metal ? "bar" : "1";
  const std::string speed_unit = metal ? "Å/ps" : "1";
  if (front_t_.size() < 3) {
    throw Error(fmt::format(
        "stage '{}': wave_front needs at least 3 samples before the first reflection; lower "
        "sample_every",
        stage));
  }
  const auto fit = analysis::fit_line(front_t_, front_s_);
  r.add_scalar("wave_speed", fit.slope, speed_unit);
  r.add_scalar("exact_wave_speed", bar_.wave_speed, speed_unit);
  if (plateau_step_ <= steps_) r.add_scalar("plateau_stress", plateau_, stress_unit);
  r.add_scalar("rms_from_exact", rms_, stress_unit);
  r.add_scalar("excess_variation", variation_, stress_unit);
  if (rms_reference_) r.add_scalar("rms_ratio_mpm_over_ddmp", *rms_reference_ / rms_, "1");
  if (variation_reference_) {
    r.add_scalar("variation_ratio_mpm_over_ddmp", *variation_reference_ / variation_, "1");
  }
  r.add_column("front", "time", metal ? "ps" : "1", front_t_);
  r.add_column("front", "distance", metal ? "Å" : "1", front_s_);
  const auto x = column(profile_, 1);
  std::vector<double> exact;
  exact.reserve(x.size());
  for (const double xi : x) exact.push_back(bar_.exact_stress(xi, profile_t_));
  r.add_column("profile", "x", metal ? "Å" : "1", x);
  r.add_column("profile", "stress_xx", stress_unit, column(profile_, 2));
  r.add_column("profile", "exact_stress_xx", stress_unit, exact);
  r.attributes["profile_time"] = fmt::format("{:.10g}", profile_t_);
}

void BarWaveAnalysis::save(CheckpointArchive& a) const {
  a.put("wave/scalars",
        std::vector<double>{static_cast<double>(plateau_step_), static_cast<double>(profile_step_),
                            plateau_, rms_, variation_, profile_t_});
  a.put("wave/front_t", front_t_);
  a.put("wave/front_s", front_s_);
  a.put("wave/profile", profile_);
}

void BarWaveAnalysis::load(const CheckpointArchive& a) {
  const auto& s = a.get("wave/scalars");
  plateau_step_ = static_cast<std::int64_t>(s.at(0));
  profile_step_ = static_cast<std::int64_t>(s.at(1));
  plateau_ = s.at(2);
  rms_ = s.at(3);
  variation_ = s.at(4);
  profile_t_ = s.at(5);
  front_t_ = a.get("wave/front_t");
  front_s_ = a.get("wave/front_s");
  profile_ = a.get("wave/profile");
}

}  // namespace pbms::mpm
