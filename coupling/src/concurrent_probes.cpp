#include "pbms/coupling/concurrent_probes.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pbms/analysis/first_crossing.hpp"
#include "pbms/analysis/front_arrival.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {
namespace {

void sum_over(MPI_Comm comm, double* v, int n) {
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, comm),
             "MPI_Allreduce (concurrent probes)");
}

}  // namespace

double grip_force(MPI_Comm comm, const std::vector<Vec3>& reactions,
                  const std::vector<std::uint32_t>& masks, std::uint32_t grip, int axis) {
  double f = 0.0;
  for (std::size_t i = 0; i < reactions.size() && i < masks.size(); ++i) {
    if ((masks[i] & grip) != 0) f += reactions[i][static_cast<std::size_t>(axis)];
  }
  sum_over(comm, &f, 1);
  return f;
}

ConcurrentProbes::ConcurrentProbes(MPI_Comm comm, const ConcurrentParams& params,
                                   const std::vector<std::string>& group_names, double bin,
                                   const ParticleView& start)
    : comm_(comm), p_(params), group_names_(group_names), bin_(bin) {
  // Every rank keeps every particle's start, since particles migrate.
  std::vector<double> mine;
  for (std::size_t i = 0; i < start.count; ++i) {
    mine.insert(mine.end(),
                {static_cast<double>(start.id[i]), start.x[i][0], start.x[i][1], start.x[i][2]});
  }
  int size = 1;
  MPI_Comm_size(comm, &size);
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(counts.size(), 0);
  mpi::check(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm),
             "MPI_Allgather (probe starts)");
  for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<double> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  mpi::check(MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(),
                            offsets.data(), MPI_DOUBLE, comm),
             "MPI_Allgatherv (probe starts)");
  for (std::size_t k = 0; k + 4 <= all.size(); k += 4) {
    start_[std::llround(all[k])] = {all[k + 1], all[k + 2], all[k + 3]};
  }
  const auto a = static_cast<std::size_t>(p_.axis);
  lo_ = p_.grid.origin()[a];
  bins_ = static_cast<std::size_t>(std::ceil((p_.grid.upper()[a] - lo_) / bin_));
  // A slab counts on the side that holds all of it.
  for (const auto& s : p_.speeds) {
    for (const auto& g : {s.near_slab, s.far_slab}) {
      if (std::find(tracked_.begin(), tracked_.end(), g) == tracked_.end() &&
          !std::isnan(displacement(g, start))) {
        tracked_.push_back(g);
      }
    }
  }
  tracked_s_.resize(tracked_.size());
  for (const auto& g : tracked_) tracked_at_.push_back(centre(mask_of(g), start));
}

double ConcurrentProbes::centre(std::uint32_t mask, const ParticleView& now) const {
  const auto a = static_cast<std::size_t>(p_.axis);
  double m[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask) == 0) continue;
    m[0] += now.mass[i];
    m[1] += now.mass[i] * now.x[i][a];
  }
  sum_over(comm_, m, 2);
  return m[0] > 0.0 ? m[1] / m[0] : std::nan("");
}

std::uint32_t ConcurrentProbes::mask_of(const std::string& group) const {
  for (std::size_t g = 0; g < group_names_.size(); ++g) {
    if (group_names_[g] == group) return std::uint32_t{1} << g;
  }
  return 0;
}

double ConcurrentProbes::displacement(const std::string& group, const ParticleView& now) const {
  return displacement(mask_of(group), now);
}

// Mass, mass-weighted displacement and mass-weighted start along the axis,
// over this side's ranks.
std::array<double, 3> ConcurrentProbes::moments(std::uint32_t mask, const ParticleView& now) const {
  const auto a = static_cast<std::size_t>(p_.axis);
  std::array<double, 3> m{};
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask) == 0) continue;
    const double x0 = start_.at(now.id[i])[a];
    m[0] += now.mass[i];
    m[1] += now.mass[i] * (now.x[i][a] - x0);
    m[2] += now.mass[i] * x0;
  }
  sum_over(comm_, m.data(), 3);
  return m;
}

double ConcurrentProbes::displacement(std::uint32_t mask, const ParticleView& now) const {
  const auto m = moments(mask, now);
  return m[0] > 0.0 ? m[1] / m[0] : std::nan("");
}

ConcurrentProbes::PlaneMoments ConcurrentProbes::opening_moments(const ParticleView& now) const {
  if (!p_.opening) return {};
  const auto d = moments(mask_of(p_.opening->first), now);
  const auto m = moments(mask_of(p_.opening->second), now);
  return {d[0], d[1], d[2], m[0], m[1], m[2]};
}

double ConcurrentProbes::opening(const PlaneMoments& mine, const PlaneMoments& theirs) {
  PlaneMoments s{};
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = mine[k] + theirs[k];
  if (s[0] <= 0.0 || s[3] <= 0.0) return std::nan("");
  const double jump = s[4] / s[3] - s[1] / s[0];
  return s[5] / s[3] > s[2] / s[0] ? jump : -jump;
}

void ConcurrentProbes::track(std::int64_t step, const ParticleView& now) {
  track_t_.push_back(static_cast<double>(step) * p_.time_step);
  for (std::size_t k = 0; k < tracked_.size(); ++k) {
    tracked_s_[k].push_back(displacement(tracked_[k], now));
  }
}

void ConcurrentProbes::sample(std::int64_t step, const ParticleView& now) {
  if (p_.profile_every > 0 && step % p_.profile_every == 0) {
    profile(static_cast<double>(step) * p_.time_step, now);
  }
}

// The mean displacement along the axis of the particles starting in each
// bin of the axis.
void ConcurrentProbes::profile(double t, const ParticleView& now) {
  const auto a = static_cast<std::size_t>(p_.axis);
  std::vector<double> sums(2 * bins_, 0.0);
  for (std::size_t i = 0; i < now.count; ++i) {
    const Vec3& x0 = start_.at(now.id[i]);
    const auto b = static_cast<std::size_t>(
        std::clamp(std::floor((x0[a] - lo_) / bin_), 0.0, static_cast<double>(bins_ - 1)));
    sums[2 * b] += 1.0;
    sums[2 * b + 1] += now.x[i][a] - x0[a];
  }
  sum_over(comm_, sums.data(), static_cast<int>(sums.size()));
  std::vector<double> mean(bins_);
  for (std::size_t b = 0; b < bins_; ++b) {
    mean[b] = sums[2 * b] > 0.0 ? sums[2 * b + 1] / sums[2 * b] : std::nan("");
  }
  profile_t_.push_back(t);
  profiles_.push_back(std::move(mean));
}

// The slabs' histories to time: their own or, with a baseline for this
// side, less the baseline's sample by sample (its response to the impact).
std::vector<std::vector<double>> ConcurrentProbes::timed_histories(
    const std::string& prefix) const {
  const auto base = p_.baseline.find(prefix);
  if (base == p_.baseline.end()) return tracked_s_;
  std::vector<std::vector<double>> out = tracked_s_;
  for (std::size_t k = 0; k < tracked_.size(); ++k) {
    const std::vector<double>& b = base->second.at(tracked_[k]);
    for (std::size_t j = 0; j < out[k].size(); ++j) out[k][j] -= b.at(j);
  }
  return out;
}

void ConcurrentProbes::report(StageResults& r, const std::string& prefix) const {
  const std::vector<std::vector<double>> timed = timed_histories(prefix);
  const bool with_baseline = p_.baseline.count(prefix) != 0;
  if (!tracked_.empty()) {
    r.add_column(prefix + "_slabs", "time", "ps", track_t_);
    for (std::size_t k = 0; k < tracked_.size(); ++k) {
      r.add_column(prefix + "_slabs", tracked_[k], "Å", tracked_s_[k]);
      if (with_baseline) r.add_column(prefix + "_slabs", tracked_[k] + "_response", "Å", timed[k]);
    }
  }
  for (const auto& s : p_.speeds) {
    const auto near = std::find(tracked_.begin(), tracked_.end(), s.near_slab);
    const auto far = std::find(tracked_.begin(), tracked_.end(), s.far_slab);
    if (near == tracked_.end() || far == tracked_.end()) continue;
    const auto in = static_cast<std::size_t>(near - tracked_.begin());
    const auto jf = static_cast<std::size_t>(far - tracked_.begin());
    const auto& sn = timed[in];
    const auto& sf = timed[jf];
    const double tn = analysis::first_crossing(track_t_, sn, p_.threshold);
    const double tf = analysis::first_crossing(track_t_, sf, p_.threshold);
    r.add_scalar("first_motion_" + s.near_slab, tn, "ps");
    r.add_scalar("first_motion_" + s.far_slab, tf, "ps");
    if (with_baseline && !std::isnan(tn)) {
      double residual = 0.0;
      for (std::size_t j = 0; j < track_t_.size() && track_t_[j] < tn; ++j) {
        residual = std::max(residual, std::abs(sf[j]));
      }
      r.add_scalar("baseline_residual_" + s.name, residual, "Å");
    }
    // Å/ps is 100 m/s.
    const double distance = std::abs(tracked_at_[jf] - tracked_at_[in]) * 100.0;
    const auto fn = analysis::mid_amplitude_arrival(track_t_, sn, tn, p_.smoothing, p_.window);
    const auto ff = analysis::mid_amplitude_arrival(track_t_, sf, tf, p_.smoothing, p_.window);
    if (ff.time > fn.time) {
      r.add_scalar("front_" + s.near_slab, fn.time, "ps");
      r.add_scalar("front_" + s.far_slab, ff.time, "ps");
      r.add_scalar("front_speed_" + s.name, distance / (ff.time - fn.time), "m/s");
    } else {
      r.attributes["front_speed_" + s.name] =
          fmt::format("not measured: no mid-amplitude arrival at both slabs ({:.4g} and {:.4g} ps)",
                      fn.time, ff.time);
    }
    if (tf > tn) {
      r.add_scalar("wave_speed_" + s.name, distance / (tf - tn), "m/s");
    } else {
      r.attributes["wave_speed_" + s.name] = fmt::format(
          "not measured: the wave did not reach both slabs (first motion {:.4g} and {:.4g} ps)", tn,
          tf);
    }
  }
  if (!profiles_.empty()) {
    std::vector<double> centre(bins_);
    for (std::size_t b = 0; b < bins_; ++b) centre[b] = lo_ + (static_cast<double>(b) + 0.5) * bin_;
    r.add_column(prefix + "_profiles", "position", "Å", centre);
    for (std::size_t k = 0; k < profiles_.size(); ++k) {
      r.add_column(prefix + "_profiles", fmt::format("t={:.3f}", profile_t_[k]), "Å", profiles_[k]);
    }
  }
}

void ConcurrentProbes::save(CheckpointArchive& a) const {
  // Sorted by id, so that the archive does not depend on the map's order.
  std::vector<std::int64_t> ids;
  ids.reserve(start_.size());
  for (const auto& [id, x] : start_) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  std::vector<double> rows;
  rows.reserve(4 * ids.size());
  for (const auto id : ids) {
    const Vec3& x = start_.at(id);
    rows.insert(rows.end(), {static_cast<double>(id), x[0], x[1], x[2]});
  }
  a.put("probes/starts", std::move(rows));
  a.put("probes/tracked_at", tracked_at_);
  a.put("probes/track_time", track_t_);
  for (std::size_t k = 0; k < tracked_s_.size(); ++k) {
    a.put(fmt::format("probes/tracked_{}", k), tracked_s_[k]);
  }
  a.put("probes/profile_time", profile_t_);
  for (std::size_t k = 0; k < profiles_.size(); ++k) {
    a.put(fmt::format("probes/profile_{}", k), profiles_[k]);
  }
}

void ConcurrentProbes::load(const CheckpointArchive& a) {
  const auto& rows = a.get("probes/starts");
  start_.clear();
  for (std::size_t k = 0; k + 4 <= rows.size(); k += 4) {
    start_[std::llround(rows[k])] = {rows[k + 1], rows[k + 2], rows[k + 3]};
  }
  tracked_at_ = a.get("probes/tracked_at");
  track_t_ = a.get("probes/track_time");
  for (std::size_t k = 0; k < tracked_s_.size(); ++k) {
    tracked_s_[k] = a.get(fmt::format("probes/tracked_{}", k));
  }
  profile_t_ = a.get("probes/profile_time");
  profiles_.assign(profile_t_.size(), {});
  for (std::size_t k = 0; k < profiles_.size(); ++k) {
    profiles_[k] = a.get(fmt::format("probes/profile_{}", k));
  }
}

}  // namespace pbms::coupling
