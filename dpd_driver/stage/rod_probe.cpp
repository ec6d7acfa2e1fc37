#include "rod_probe.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "pbms/analysis/rod_bend.hpp"
#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"

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
  // Slabs of a, the first centred on the rod's lowest plane.
  lo_ = range[0] - 0.5 * a_;
  slabs_ = static_cast<std::size_t>(std::floor((-range[1] - lo_) / a_)) + 1;
}

void RodProbe::sample(double t, const coupling::ParticleView& now) {
  const auto axis = static_cast<std::size_t>(spec_.axis);
  std::vector<std::array<double, 4>> sums(slabs_, {0.0, 0.0, 0.0, 0.0});
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask_) == 0U) continue;
    const double k = std::floor((now.x[i][axis] - lo_) / a_);
    const auto s = static_cast<std::size_t>(std::clamp(k, 0.0, static_cast<double>(slabs_ - 1)));
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
}

void RodProbe::load(const CheckpointArchive& a) {
  time_ = a.get("rod_" + spec_.name + "/time");
  bend_ = a.get("rod_" + spec_.name + "/bend");
}

}  // namespace pbms::dpd
