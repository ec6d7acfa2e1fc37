#include "neck_probe.hpp"

#include <array>

#include "pbms/analysis/neck_width.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/mpi/sorted_rows.hpp"

namespace pbms::dpd {

NeckProbe::NeckProbe(MPI_Comm comm, coupling::NeckPair spec, std::uint32_t first,
                     std::uint32_t second, double a)
    : comm_(comm),
      first_(first),
      second_(second),
      rod_axis_(spec.second_rod_axis),
      a_(a),
      history_(std::move(spec.name), a) {}

void NeckProbe::sample(double t, const coupling::ParticleView& now) {
  // The two bodies' centres of mass, then their members per slab.
  std::array<std::array<double, 4>, 2> sums{};  // each body: m, m x, m y, m z
  for (std::size_t i = 0; i < now.count; ++i) {
    const bool in_first = (now.groups[i] & first_) != 0U;
    if (!in_first && (now.groups[i] & second_) == 0U) continue;
    auto& s = sums[in_first ? 0 : 1];
    s[0] += now.mass[i];
    for (std::size_t c = 0; c < 3; ++c) s[1 + c] += now.mass[i] * now.x[i][c];
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, sums.data(), 8, MPI_DOUBLE, MPI_SUM, comm_),
             "MPI_Allreduce (neck centres)");
  const analysis::NeckSlabs slabs(sums[0], sums[1], a_, rod_axis_);
  std::vector<double> count(slabs.slabs(), 0.0);
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & (first_ | second_)) == 0U) continue;
    if (const auto k = slabs.slab_of(now.x[i])) count[*k] += 1.0;
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, count.data(), static_cast<int>(count.size()), MPI_DOUBLE,
                           MPI_SUM, comm_),
             "MPI_Allreduce (neck slabs)");
  history_.add(t, {slabs.width(count), slabs.centre_distance(), closest(now)});
}

double NeckProbe::closest(const coupling::ParticleView& now) const {
  // Both bodies' members on every rank: a closest pair may straddle ranks.
  std::vector<double> rows;
  for (std::size_t i = 0; i < now.count; ++i) {
    const bool in_first = (now.groups[i] & first_) != 0U;
    if (!in_first && (now.groups[i] & second_) == 0U) continue;
    rows.insert(rows.end(), {in_first ? 0.0 : 1.0, now.x[i][0], now.x[i][1], now.x[i][2]});
  }
  const auto all = mpi::sorted_rows(comm_, rows, 4, mpi::RowsTo::kEveryRank);
  std::array<std::vector<std::array<double, 3>>, 2> members;
  for (std::size_t k = 0; k + 3 < all.size(); k += 4) {
    members[all[k] == 0.0 ? 0 : 1].push_back({all[k + 1], all[k + 2], all[k + 3]});
  }
  return analysis::closest_approach(members[0], members[1], analysis::closest_reach(a_));
}

void NeckProbe::report(StageResults& r, double stable_time) const {
  history_.report(r, stable_time);
}

void NeckProbe::save(CheckpointArchive& a) const {
  history_.save(a);
}

void NeckProbe::load(const CheckpointArchive& a) {
  history_.load(a);
}

}  // namespace pbms::dpd
