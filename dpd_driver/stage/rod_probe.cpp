#include "rod_probe.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "pbms/analysis/rod_bend.hpp"
#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/mpi/sorted_rows.hpp"

namespace pbms::dpd {

RodProbe::RodProbe(MPI_Comm comm, coupling::RodBend spec, std::uint32_t mask, double a,
                   const coupling::ParticleView& now)
    : comm_(comm), spec_(std::move(spec)), mask_(mask), a_(a) {
  const auto axis = static_cast<std::size_t>(spec_.axis);
  double range[2] = {std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::infinity()};  // lo, -hi
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask_) == 0U) continue;
    range[0] = std::min(range[0], now.x[i][axis]);
    range[1] = std::min(range[1], -now.x[i][axis]);
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, range, 2, MPI_DOUBLE, MPI_MIN, comm_),
             "MPI_Allreduce (rod extent)");
  if (!std::isfinite(range[0])) throw StageFailure("rod '" + spec_.name + "': its group is empty");
  // Slabs of a along a <100> axis hold two whole planes each (planes a/2
  // apart): their bounds fall midway between planes, where thermal motion
  // does not carry a particle across. The planes are placed by all the
  // rod's particles, not by its lowest one: a particle out of a rough end
  // face (2.4 Å in the assemblies' rod) put the bounds 0.6 Å from a plane.
  const double h = 0.5 * a_;
  const double phase = plane_phase(now, h);
  const double first = phase + h * std::floor((range[0] - phase) / h + 0.5);
  lo_ = first - 0.5 * h;
  slabs_ = static_cast<std::size_t>(std::floor((-range[1] - lo_) / a_)) + 1;
  assign_slabs(now);
}

// Where the planes normal to the axis sit, modulo their spacing h: the
// angle of the mean of exp(2 pi i z / h) over the rod's particles.
double RodProbe::plane_phase(const coupling::ParticleView& now, double h) const {
  const auto axis = static_cast<std::size_t>(spec_.axis);
  const double k = 2.0 * std::numbers::pi / h;
  double sum[2] = {0.0, 0.0};  // cos, sin
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask_) == 0U) continue;
    sum[0] += std::cos(k * now.x[i][axis]);
    sum[1] += std::sin(k * now.x[i][axis]);
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, sum, 2, MPI_DOUBLE, MPI_SUM, comm_),
             "MPI_Allreduce (rod planes)");
  return std::atan2(sum[1], sum[0]) / k;
}

// Each rank keeps the whole rod's (id, slab) pairs: particles change rank
// as they move, and a rod is thousands of particles.
void RodProbe::assign_slabs(const coupling::ParticleView& now) {
  const auto axis = static_cast<std::size_t>(spec_.axis);
  std::vector<double> mine;  // rows of (id, slab)
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask_) == 0U) continue;
    const double k = std::floor((now.x[i][axis] - lo_) / a_);
    mine.push_back(static_cast<double>(now.id[i]));
    mine.push_back(std::clamp(k, 0.0, static_cast<double>(slabs_ - 1)));
  }
  const auto all = mpi::sorted_rows(comm_, mine, 2, mpi::RowsTo::kEveryRank);
  ids_.clear();
  slab_of_.clear();
  for (std::size_t j = 0; j + 1 < all.size(); j += 2) {
    ids_.push_back(static_cast<std::int64_t>(all[j]));
    slab_of_.push_back(static_cast<std::uint32_t>(all[j + 1]));
  }
}

std::optional<std::size_t> RodProbe::slab_of(std::int64_t id) const {
  const auto it = std::lower_bound(ids_.begin(), ids_.end(), id);
  if (it == ids_.end() || *it != id) return std::nullopt;
  return slab_of_[static_cast<std::size_t>(it - ids_.begin())];
}

void RodProbe::sample(double t, const coupling::ParticleView& now) {
  std::vector<std::array<double, 4>> sums(slabs_, {0.0, 0.0, 0.0, 0.0});
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask_) == 0U) continue;
    const auto slab = slab_of(now.id[i]);
    if (!slab) continue;
    const std::size_t s = *slab;
    sums[s][0] += 1.0;
    for (std::size_t c = 0; c < 3; ++c) sums[s][1 + c] += now.x[i][c];
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(4 * slabs_), MPI_DOUBLE,
                           MPI_SUM, comm_),
             "MPI_Allreduce (rod slabs)");
  time_.push_back(t);
  bend_.push_back(analysis::rod_bend(sums));
}

void RodProbe::report(StageResults& r) const {
  if (time_.empty()) return;
  r.add_column("rod_" + spec_.name, "time", "ps", time_);
  r.add_column("rod_" + spec_.name, "bend", "Å", bend_);
  r.add_scalar("rod_deflection_" + spec_.name, *std::max_element(bend_.begin(), bend_.end()), "Å");
  r.add_scalar("rod_bend_initial_" + spec_.name, bend_.front(), "Å");
}

void RodProbe::save(CheckpointArchive& a) const {
  a.put("rod_" + spec_.name + "/time", time_);
  a.put("rod_" + spec_.name + "/bend", bend_);
  // Ids as doubles: exact below 2^53.
  a.put("rod_" + spec_.name + "/ids", std::vector<double>(ids_.begin(), ids_.end()));
  a.put("rod_" + spec_.name + "/slabs", std::vector<double>(slab_of_.begin(), slab_of_.end()));
}

void RodProbe::load(const CheckpointArchive& a) {
  time_ = a.get("rod_" + spec_.name + "/time");
  bend_ = a.get("rod_" + spec_.name + "/bend");
  // A checkpoint from before the slabs were kept: they stay as the resumed
  // positions put them.
  if (!a.has("rod_" + spec_.name + "/ids")) return;
  const auto& ids = a.get("rod_" + spec_.name + "/ids");
  const auto& slabs = a.get("rod_" + spec_.name + "/slabs");
  ids_.assign(ids.size(), 0);
  slab_of_.assign(slabs.size(), 0U);
  std::transform(ids.begin(), ids.end(), ids_.begin(),
                 [](double v) { return static_cast<std::int64_t>(v); });
  std::transform(slabs.begin(), slabs.end(), slab_of_.begin(),
                 [](double v) { return static_cast<std::uint32_t>(v); });
}

}  // namespace pbms::dpd
