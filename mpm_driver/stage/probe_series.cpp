#include "probe_series.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::mpm {
namespace {

void allreduce(MPI_Comm comm, const std::vector<double>& in, std::vector<double>& out, MPI_Op op) {
  out.resize(in.size());
  if (in.empty()) return;
  mpi::check(
      MPI_Allreduce(in.data(), out.data(), static_cast<int>(in.size()), MPI_DOUBLE, op, comm),
      "MPI_Allreduce (probes)");
}

}  // namespace

ProbeSeries::ProbeSeries(const std::vector<ProbeSpec>& probes, const MpmModel& model,
                         bool metal_units)
    : probes_(probes, model, metal_units), columns_(probes_.columns().size()) {}

void ProbeSeries::sample(const MpmEngine& engine, std::int64_t step, double t) {
  probes_.local(engine.points(), engine.solver(), engine.model().bc, sums_, maxima_);
  allreduce(engine.comm(), sums_, reduced_sums_, MPI_SUM);
  allreduce(engine.comm(), maxima_, reduced_max_, MPI_MAX);
  auto values = probes_.values(reduced_sums_, reduced_max_);
  if (step == 0) {
    probes_.set_reference(values);
    values = probes_.values(reduced_sums_, reduced_max_);
  }
  for (std::size_t c = 0; c < values.size(); ++c) columns_[c].push_back(values[c]);
  step_.push_back(static_cast<double>(step));
  time_.push_back(t);
}

void ProbeSeries::report(StageResults& r, const MpmRunParams& params,
                         const std::string& stage) const {
  const std::string time_unit = params.time_unit();
  r.add_column("probes", "step", "1", step_);
  r.add_column("probes", "time", time_unit, time_);
  for (std::size_t c = 0; c < columns_.size(); ++c)
    r.add_column("probes", probes_.columns()[c], probes_.units()[c], columns_[c]);
  if (probes_.has_energy()) {
    const auto& e = columns_[static_cast<std::size_t>(probes_.energy_total_column())];
    const double e0 = e.front();
    double dev = 0.0;
    for (const double v : e) dev = std::max(dev, std::abs(v - e0));
    const double scale = std::abs(e0) > 0.0 ? std::abs(e0) : 1.0;
    r.add_scalar("energy_drift", (e.back() - e0) / scale, "1");
    r.add_scalar("energy_max_deviation", dev / scale, "1");
  }
  if (params.period_of.empty()) return;
  const auto& names = probes_.columns();
  const auto it = std::find(names.begin(), names.end(), params.period_of);
  if (it == names.end()) {
    throw Error(fmt::format("stage '{}': period_of names no probe column ('{}'); columns: {}",
                            stage, params.period_of, fmt::join(names, ", ")));
  }
  r.add_scalar(
      "period",
      analysis::oscillation_period(time_, columns_[static_cast<std::size_t>(it - names.begin())]),
      time_unit);
}

void ProbeSeries::save(CheckpointArchive& a) const {
  a.put("probes/step", step_);
  a.put("probes/time", time_);
  a.put("probes/reference", probes_.reference());
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    a.put(fmt::format("probes/column_{}", c), columns_[c]);
  }
}

void ProbeSeries::load(const CheckpointArchive& a) {
  step_ = a.get("probes/step");
  time_ = a.get("probes/time");
  if (!a.get("probes/reference").empty()) probes_.set_reference(a.get("probes/reference"));
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    columns_[c] = a.get(fmt::format("probes/column_{}", c));
  }
}

}  // namespace pbms::mpm
