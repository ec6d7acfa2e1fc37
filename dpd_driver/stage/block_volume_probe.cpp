#include "block_volume_probe.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::dpd {
namespace {

// Every rank's ids, gathered on every rank and sorted.
std::vector<std::int64_t> all_ids(MPI_Comm comm, const std::vector<std::int64_t>& mine) {
  int ranks = 0;
  MPI_Comm_size(comm, &ranks);
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks)), offsets(counts.size());
  mpi::check(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm), "MPI_Allgather");
  int total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = total;
    total += counts[r];
  }
  std::vector<std::int64_t> ids(static_cast<std::size_t>(total));
  mpi::check(MPI_Allgatherv(mine.data(), n, MPI_INT64_T, ids.data(), counts.data(), offsets.data(),
                            MPI_INT64_T, comm),
             "MPI_Allgatherv (block planes)");
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace

BlockVolumeProbe::BlockVolumeProbe(MPI_Comm comm, const coupling::VolumeProbe& probe,
                                   std::uint32_t mask, double a, const coupling::ParticleView& now)
    : comm_(comm), probe_(probe), half_plane_(0.5 * a) {
  // Extremes along each axis: -lo and hi, so one MAX reduction does both.
  std::array<double, 6> extreme;
  extreme.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask) == 0U) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      extreme[2 * c] = std::max(extreme[2 * c], -now.x[i][c]);
      extreme[2 * c + 1] = std::max(extreme[2 * c + 1], now.x[i][c]);
    }
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, extreme.data(), 6, MPI_DOUBLE, MPI_MAX, comm),
             "MPI_Allreduce (block extremes)");
  // A plane's particles lie within a quarter plane spacing of its extreme
  // (thermal motion is a small part of that).
  const double band = 0.25 * half_plane_;
  std::array<std::vector<std::int64_t>, 6> mine;
  for (std::size_t i = 0; i < now.count; ++i) {
    if ((now.groups[i] & mask) == 0U) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      if (-now.x[i][c] >= extreme[2 * c] - band) mine[2 * c].push_back(now.id[i]);
      if (now.x[i][c] >= extreme[2 * c + 1] - band) mine[2 * c + 1].push_back(now.id[i]);
    }
  }
  for (std::size_t k = 0; k < 6; ++k) {
    planes_[k] = all_ids(comm, mine[k]);
    if (planes_[k].empty()) {
      throw Error(fmt::format("volume: group '{}' holds no DPD particle", probe.group));
    }
  }
  const auto m = plane_means(now);
  for (std::size_t c = 0; c < 3; ++c) start_[c] = m[2 * c + 1] - m[2 * c];
}

std::array<double, 6> BlockVolumeProbe::plane_means(const coupling::ParticleView& now) const {
  std::array<double, 12> sums{};  // per plane: sum of coordinates, count
  for (std::size_t i = 0; i < now.count; ++i) {
    for (std::size_t k = 0; k < 6; ++k) {
      if (!std::binary_search(planes_[k].begin(), planes_[k].end(), now.id[i])) continue;
      sums[2 * k] += now.x[i][k / 2];
      sums[2 * k + 1] += 1.0;
    }
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, sums.data(), 12, MPI_DOUBLE, MPI_SUM, comm_),
             "MPI_Allreduce (block planes)");
  std::array<double, 6> means{};
  for (std::size_t k = 0; k < 6; ++k) means[k] = sums[2 * k] / sums[2 * k + 1];
  return means;
}

void BlockVolumeProbe::sample(double t, const coupling::ParticleView& now) {
  const auto m = plane_means(now);
  double v = 1.0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double d = m[2 * c + 1] - m[2 * c];
    const double edge = d * (start_[c] + half_plane_) / start_[c];
    edges_[c].push_back(edge);
    v *= edge;
  }
  time_.push_back(t);
  volume_.push_back(v);
}

void BlockVolumeProbe::report(StageResults& r) const {
  if (volume_.empty()) return;
  r.add_column("body_edges", "time", "ps", time_);
  for (std::size_t c = 0; c < 3; ++c) {
    r.add_column("body_edges", fmt::format("edge_{}", "xyz"[c]), "Å", edges_[c]);
  }
  r.add_column("body_edges", "volume", "Å^3", volume_);
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
  for (std::size_t c = 0; c < 3; ++c) a.put(fmt::format("volume/edge_{}", c), edges_[c]);
}

void BlockVolumeProbe::load(const CheckpointArchive& a) {
  time_ = a.get("volume/time");
  volume_ = a.get("volume/volume");
  for (std::size_t c = 0; c < 3; ++c) edges_[c] = a.get(fmt::format("volume/edge_{}", c));
}

}  // namespace pbms::dpd
