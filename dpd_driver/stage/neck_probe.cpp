#include "neck_probe.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pbms/mpi/comm.hpp"

namespace pbms::dpd {

NeckProbe::NeckProbe(MPI_Comm comm, coupling::NeckPair spec, std::uint32_t first,
                     std::uint32_t second, double a)
    : comm_(comm), spec_(std::move(spec)), first_(first), second_(second), a_(a) {}

void NeckProbe::sample(double t, const coupling::ParticleView& now) {
  // Centres of mass of the two bodies.
  double sums[8] = {};  // first: m, m x; second: m, m x
  for (std::size_t i = 0; i < now.count; ++i) {
    const bool in_first = (now.groups[i] & first_) != 0U;
    const bool in_second = (now.groups[i] & second_) != 0U;
    if (!in_first && !in_second) continue;
    double* s = in_first ? sums : sums + 4;
    s[0] += now.mass[i];
    for (std::size_t c = 0; c < 3; ++c) s[1 + c] += now.mass[i] * now.x[i][c];
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, sums, 8, MPI_DOUBLE, MPI_SUM, comm_),
             "MPI_Allreduce (neck centres)");
  std::array<double, 3> c0{}, axis{};
  double length = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    c0[c] = sums[1 + c] / sums[0];
    axis[c] = sums[5 + c] / sums[4] - c0[c];
    length += axis[c] * axis[c];
  }
  length = std::sqrt(length);
  for (double& u : axis) u /= length;
  // Particles of either body per slab one plane spacing (a/2) thick along
  // the axis, over the middle half of the line between the centres, a slab
  // centred on its midpoint (so that a gap of a plane spacing shows).
  const double slab = 0.5 * a_;
  const auto half = static_cast<std::size_t>(std::max(0.0, std::floor(0.25 * length / slab - 0.5)));
  const std::size_t slabs = 2 * half + 1;
  const double from = 0.5 * length - (static_cast<double>(half) + 0.5) * slab;
  std::vector<double> count(slabs, 0.0);
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & (first_ | second_)) == 0U) continue;
    double s = 0.0;
    for (std::size_t c = 0; c < 3; ++c) s += (now.x[i][c] - c0[c]) * axis[c];
    const double k = std::floor((s - from) / slab);
    if (k >= 0.0 && k < static_cast<double>(slabs)) count[static_cast<std::size_t>(k)] += 1.0;
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, count.data(), static_cast<int>(slabs), MPI_DOUBLE, MPI_SUM,
                           comm_),
             "MPI_Allreduce (neck slabs)");
  const double fewest = *std::min_element(count.begin(), count.end());
  const double area = fewest * (a_ * a_ * a_ / 4.0) / slab;
  time_.push_back(t);
  width_.push_back(2.0 * std::sqrt(area / std::numbers::pi));
  distance_.push_back(length);
}

void NeckProbe::report(StageResults& r, double stable_time) const {
  if (time_.empty()) return;
  const std::string table = "neck_" + spec_.name;
  r.add_column(table, "time", "ps", time_);
  r.add_column(table, "width", "Å", width_);
  r.add_column(table, "centre_distance", "Å", distance_);
  double sum = 0.0, n = 0.0;
  for (std::size_t k = 0; k < time_.size(); ++k) {
    if (time_[k] < time_.back() - stable_time - 1e-9) continue;
    sum += width_[k];
    n += 1.0;
  }
  r.add_scalar("neck_width_" + spec_.name, sum / n, "Å");
  r.add_scalar("neck_final_" + spec_.name, width_.back(), "Å");
  for (std::size_t k = 0; k < time_.size(); ++k) {
    if (width_[k] > 0.0) {
      r.add_scalar("contact_time_" + spec_.name, time_[k], "ps");
      break;
    }
  }
}

void NeckProbe::save(CheckpointArchive& a) const {
  a.put("neck_" + spec_.name + "/time", time_);
  a.put("neck_" + spec_.name + "/width", width_);
  a.put("neck_" + spec_.name + "/distance", distance_);
}

void NeckProbe::load(const CheckpointArchive& a) {
  time_ = a.get("neck_" + spec_.name + "/time");
  width_ = a.get("neck_" + spec_.name + "/width");
  distance_ = a.get("neck_" + spec_.name + "/distance");
}

}  // namespace pbms::dpd
