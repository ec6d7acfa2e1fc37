#include "block_volume_probe.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/mpi/sorted_rows.hpp"

namespace pbms::dpd {
namespace {

// The block's particles, [id, x, y, z] rows sorted by id, on every rank.
std::vector<double> gathered_block(MPI_Comm comm, std::uint32_t mask,
                                   const coupling::ParticleView& now) {
  std::vector<double> mine;
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask) == 0U) continue;
    mine.insert(mine.end(),
                {static_cast<double>(now.id[i]), now.x[i][0], now.x[i][1], now.x[i][2]});
  }
  return mpi::sorted_rows(comm, mine, 4, mpi::RowsTo::kEveryRank);
}

}  // namespace

BlockVolumeProbe::BlockVolumeProbe(MPI_Comm comm, const coupling::VolumeProbe& probe,
                                   std::uint32_t mask, double a, const coupling::ParticleView& now)
    : comm_(comm), probe_(probe) {
  const std::vector<double> rows = gathered_block(comm, mask, now);
  std::vector<analysis::BlockPoint> x;
  for (std::size_t r = 0; r + 3 < rows.size(); r += 4) {
    ids_.push_back(static_cast<std::int64_t>(rows[r]));
    x.push_back({rows[r + 1], rows[r + 2], rows[r + 3]});
  }
  if (x.empty()) throw Error(fmt::format("volume: group '{}' holds no DPD particle", probe.group));
  try {
    sites_ = analysis::fit_block_sites(x, 0.5 * a);
  } catch (const Error& e) {
    throw Error(fmt::format("volume: group '{}': {}", probe.group, e.what()));
  }
}

analysis::BlockEdges BlockVolumeProbe::measure(const coupling::ParticleView& now) const {
  analysis::BlockSums sums;
  for (std::size_t i = 0; i < now.count; ++i) {
    const auto it = std::lower_bound(ids_.begin(), ids_.end(), now.id[i]);
    if (it == ids_.end() || *it != now.id[i]) continue;
    sums.add(sites_, static_cast<std::size_t>(it - ids_.begin()), now.x[i]);
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, sums.sums.data(), static_cast<int>(sums.sums.size()),
                           MPI_DOUBLE, MPI_SUM, comm_),
             "MPI_Allreduce (block sums)");
  return analysis::block_edges(sites_, sums);
}

void BlockVolumeProbe::sample(double t, const coupling::ParticleView& now) {
  const analysis::BlockEdges e = measure(now);
  for (std::size_t c = 0; c < 3; ++c) edges_[c].push_back(e.edge[c]);
  time_.push_back(t);
  volume_.push_back(e.volume);
  rotation_.push_back(e.rotation_deg);
}

void BlockVolumeProbe::report(StageResults& r) const {
  if (volume_.empty()) return;
  r.add_column("body_edges", "time", "ps", time_);
  for (std::size_t c = 0; c < 3; ++c) {
    r.add_column("body_edges", fmt::format("edge_{}", "xyz"[c]), "Å", edges_[c]);
  }
  r.add_column("body_edges", "volume", "Å^3", volume_);
  r.add_column("body_edges", "rotation", "deg", rotation_);
  const std::size_t from = volume_.size() / 2;
  double sum = 0.0;
  for (std::size_t k = from; k < volume_.size(); ++k) sum += volume_[k];
  const double mean = sum / static_cast<double>(volume_.size() - from);
  r.add_scalar("body_volume", mean, "Å^3");
  r.add_scalar("volume_ratio", mean / probe_.reference.value_or(volume_.front()), "1");
}

void BlockVolumeProbe::save(CheckpointArchive& a) const {
  a.put("volume/time", time_);
  a.put("volume/volume", volume_);
  a.put("volume/rotation", rotation_);
  for (std::size_t c = 0; c < 3; ++c) a.put(fmt::format("volume/edge_{}", c), edges_[c]);
}

void BlockVolumeProbe::load(const CheckpointArchive& a) {
  time_ = a.get("volume/time");
  volume_ = a.get("volume/volume");
  if (!a.has("volume/rotation")) {
    throw Error(
        "volume: the checkpoint was written before block volumes were measured along the "
        "block's own axes; run the stage again from its start");
  }
  rotation_ = a.get("volume/rotation");
  for (std::size_t c = 0; c < 3; ++c) edges_[c] = a.get(fmt::format("volume/edge_{}", c));
}

}  // namespace pbms::dpd
