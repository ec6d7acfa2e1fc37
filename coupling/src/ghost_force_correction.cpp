#include "pbms/coupling/ghost_force_correction.hpp"

#include <algorithm>
#include <cmath>

#include "pbms/error.hpp"
#include "pbms/mpi/sorted_rows.hpp"

namespace pbms::coupling {
namespace {

constexpr std::size_t kRow = 5;  // id, part, then a force
constexpr const char* kFileIdentity = "pbms ghost-force dead loads";

template <class ById>
std::vector<double> rows_of(const ById& by_id) {
  std::vector<double> rows;
  rows.reserve(kRow * by_id.size());
  for (const auto& [id, e] : by_id) {
    rows.insert(rows.end(), {static_cast<double>(id), static_cast<double>(e.part), e.force[0],
                             e.force[1], e.force[2]});
  }
  return rows;
}

template <class ById>
void add_rows(ById& by_id, const std::vector<double>& rows) {
  for (std::size_t k = 0; k + kRow <= rows.size(); k += kRow) {
    auto& e = by_id[std::llround(rows[k])];
    e.part = static_cast<int>(std::lround(rows[k + 1]));
    for (std::size_t a = 0; a < 3; ++a) e.force[a] += rows[k + 2 + a];
  }
}

}  // namespace

GhostForceCorrection::GhostForceCorrection(MPI_Comm comm, std::int64_t average_steps)
    : comm_(comm), average_steps_(average_steps) {
  if (average_steps < 1) throw Error("ghost-force correction: average over at least one step");
}

GhostForceCorrection GhostForceCorrection::read(MPI_Comm comm, const std::filesystem::path& file) {
  const CheckpointArchive a = CheckpointArchive::read(file, kFileIdentity, comm);
  GhostForceCorrection g(comm, 1);
  g.steps_ = 1;
  add_rows(g.dead_, a.get("ghost_forces/dead"));
  g.net_removed_ = a.scalar("ghost_forces/net_removed");
  return g;
}

bool GhostForceCorrection::rank_zero() const {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  return rank == 0;
}

void GhostForceCorrection::correct(std::span<const std::int64_t> id, std::span<const int> part,
                                   std::span<Vec3> force) {
  if (id.size() != force.size() || part.size() != force.size()) {
    throw Error("ghost-force correction: ids, parts and forces differ in number");
  }
  if (measured()) {
    for (std::size_t i = 0; i < id.size(); ++i) {
      const auto it = dead_.find(id[i]);
      if (it == dead_.end()) continue;
      for (std::size_t a = 0; a < 3; ++a) force[i][a] -= it->second.force[a];
    }
    return;
  }
  ++steps_;
  const auto n = static_cast<double>(steps_);
  for (std::size_t i = 0; i < id.size(); ++i) {
    // A point with no partner takes exactly nothing: no entry for it.
    if (force[i] == Vec3{0.0, 0.0, 0.0} && sum_.count(id[i]) == 0) continue;
    Entry& s = sum_[id[i]];
    s.part = part[i];
    for (std::size_t a = 0; a < 3; ++a) {
      s.force[a] += force[i][a];
      force[i][a] -= s.force[a] / n;
    }
  }
  if (measured()) pool();
}

// Every rank ends with every point's dead load: a point that moved between
// ranks while the mean was taken left part of its sum on each.
void GhostForceCorrection::pool() {
  const std::vector<double> all =
      mpi::sorted_rows(comm_, rows_of(sum_), kRow, mpi::RowsTo::kEveryRank);
  sum_.clear();
  add_rows(dead_, all);
  for (auto& [id, e] : dead_) {
    for (double& c : e.force) c /= static_cast<double>(average_steps_);
  }
  balance_parts();
}

void GhostForceCorrection::balance_parts() {
  std::unordered_map<int, std::pair<Vec3, double>> net;  // part: sum, points
  for (const auto& [id, e] : dead_) {
    auto& [sum, count] = net[e.part];
    for (std::size_t a = 0; a < 3; ++a) sum[a] += e.force[a];
    count += 1.0;
  }
  for (const auto& [part, n] : net) {
    net_removed_ = std::max(net_removed_, std::hypot(n.first[0], n.first[1], n.first[2]));
  }
  for (auto& [id, e] : dead_) {
    const auto& [sum, count] = net[e.part];
    for (std::size_t a = 0; a < 3; ++a) e.force[a] -= sum[a] / count;
  }
}

double GhostForceCorrection::largest() const {
  double m = 0.0;
  for (const auto& [id, e] : dead_) {
    m = std::max(m, std::hypot(e.force[0], e.force[1], e.force[2]));
  }
  return m;
}

void GhostForceCorrection::write(const std::filesystem::path& file) const {
  CheckpointArchive a;
  a.put_rows("ghost_forces/dead", rank_zero() ? rows_of(dead_) : std::vector<double>{}, kRow);
  a.put("ghost_forces/net_removed", net_removed_);
  a.write(file, kFileIdentity, comm_);
}

// The dead loads, which every rank holds, as rank 0 holds them; each
// rank's share of the sums while they are taken, which a resumed run's
// rank 0 takes whole (the pool at the last averaged step adds the shares).
void GhostForceCorrection::save(CheckpointArchive& a) const {
  a.put("ghost_forces/steps", static_cast<double>(steps_));
  a.put_rows("ghost_forces/sums", rows_of(sum_), kRow);
  a.put_rows("ghost_forces/dead", rank_zero() ? rows_of(dead_) : std::vector<double>{}, kRow);
  a.put("ghost_forces/net_removed", net_removed_);
}

void GhostForceCorrection::load(const CheckpointArchive& a) {
  steps_ = std::llround(a.scalar("ghost_forces/steps"));
  sum_.clear();
  dead_.clear();
  if (rank_zero()) add_rows(sum_, a.get("ghost_forces/sums"));
  add_rows(dead_, a.get("ghost_forces/dead"));
  net_removed_ = a.scalar("ghost_forces/net_removed");
}

}  // namespace pbms::coupling
