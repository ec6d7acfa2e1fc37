#include "pbms/mpi/id_rows.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <string>

#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::mpi {
namespace {

constexpr std::uint64_t kMissing = std::numeric_limits<std::uint64_t>::max();

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> d(counts.size(), 0);
  for (std::size_t r = 1; r < counts.size(); ++r) d[r] = d[r - 1] + counts[r - 1];
  return d;
}

// Ids sent to the ranks that own them, and the way back for the answers.
struct Routed {
  std::vector<std::int64_t> received;
  std::vector<int> counts, displs, recv_counts, recv_displs;
  std::vector<std::size_t> slot;  // each id's place in the send order; npos: not sent
  [[nodiscard]] std::size_t sent() const {
    return static_cast<std::size_t>(displs.back() + counts.back());
  }
};

// `owner` says -1 for an id no rank owns; that id is not sent.
template <class Owner>
Routed route(MPI_Comm comm, int size, const std::vector<std::int64_t>& ids, Owner owner) {
  Routed r;
  r.counts.assign(static_cast<std::size_t>(size), 0);
  std::vector<int> to(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    to[i] = owner(ids[i]);
    if (to[i] >= 0) ++r.counts[static_cast<std::size_t>(to[i])];
  }
  r.displs = displacements(r.counts);
  auto at = r.displs;
  std::vector<std::int64_t> send(r.sent());
  r.slot.assign(ids.size(), std::string::npos);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (to[i] < 0) continue;
    r.slot[i] = static_cast<std::size_t>(at[static_cast<std::size_t>(to[i])]++);
    send[r.slot[i]] = ids[i];
  }
  r.recv_counts.resize(r.counts.size());
  check(MPI_Alltoall(r.counts.data(), 1, MPI_INT, r.recv_counts.data(), 1, MPI_INT, comm),
        "MPI_Alltoall");
  r.recv_displs = displacements(r.recv_counts);
  r.received.resize(static_cast<std::size_t>(r.recv_displs.back() + r.recv_counts.back()));
  check(MPI_Alltoallv(send.data(), r.counts.data(), r.displs.data(), MPI_INT64_T, r.received.data(),
                      r.recv_counts.data(), r.recv_displs.data(), MPI_INT64_T, comm),
        "MPI_Alltoallv");
  return r;
}

}  // namespace

IdRows::IdRows(MPI_Comm comm, const std::vector<std::int64_t>& ids) : comm_(comm) {
  check(MPI_Comm_size(comm, &size_), "MPI_Comm_size");
  std::int64_t lo = std::numeric_limits<std::int64_t>::max();
  std::int64_t hi = std::numeric_limits<std::int64_t>::min();
  for (const std::int64_t id : ids) {
    lo = std::min(lo, id);
    hi = std::max(hi, id);
  }
  const std::uint64_t n = ids.size();
  std::int64_t max = 0;
  check(MPI_Allreduce(&lo, &min_, 1, MPI_INT64_T, MPI_MIN, comm), "MPI_Allreduce");
  check(MPI_Allreduce(&hi, &max, 1, MPI_INT64_T, MPI_MAX, comm), "MPI_Allreduce");
  check(MPI_Allreduce(&n, &total_, 1, MPI_UINT64_T, MPI_SUM, comm), "MPI_Allreduce");
  if (total_ == 0) return;
  // Unsigned, so that ids spread over the whole int64 range do not overflow.
  const std::uint64_t span = static_cast<std::uint64_t>(max) - static_cast<std::uint64_t>(min_);
  dense_ = span == total_ - 1;
  bucket_ = span / static_cast<std::uint64_t>(size_) + 1;

  // Every id goes to its range's owner once, even for a dense set: that is
  // where a repeated id shows without any rank holding all of them.
  slice_ = route(comm, size_, ids, [&](std::int64_t id) { return owner(id); }).received;
  std::sort(slice_.begin(), slice_.end());
  // Every rank throws, so that none is left waiting in a collective call.
  int repeated = std::adjacent_find(slice_.begin(), slice_.end()) != slice_.end() ? 1 : 0;
  check(MPI_Allreduce(MPI_IN_PLACE, &repeated, 1, MPI_INT, MPI_MAX, comm), "MPI_Allreduce");
  if (repeated != 0) throw Error("particle ids are not unique across ranks");
  if (dense_) {
    slice_ = {};
    return;
  }
  const std::uint64_t mine = slice_.size();
  check(MPI_Exscan(&mine, &slice_row0_, 1, MPI_UINT64_T, MPI_SUM, comm), "MPI_Exscan");
  int rank = 0;
  check(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank");
  if (rank == 0) slice_row0_ = 0;  // MPI_Exscan leaves rank 0's result undefined
}

int IdRows::owner(std::int64_t id) const {
  const std::uint64_t offset = static_cast<std::uint64_t>(id) - static_cast<std::uint64_t>(min_);
  return offset / bucket_ < static_cast<std::uint64_t>(size_) ? static_cast<int>(offset / bucket_)
                                                              : -1;
}

std::vector<std::uint64_t> IdRows::ask_owners(const std::vector<std::int64_t>& ids) const {
  const Routed r = route(comm_, size_, ids, [&](std::int64_t id) { return owner(id); });
  std::vector<std::uint64_t> answers(r.received.size());
  for (std::size_t k = 0; k < answers.size(); ++k) {
    const std::int64_t id = r.received[k];
    const auto it = std::lower_bound(slice_.begin(), slice_.end(), id);
    answers[k] = it != slice_.end() && *it == id
                     ? slice_row0_ + static_cast<std::uint64_t>(it - slice_.begin())
                     : kMissing;
  }
  std::vector<std::uint64_t> replies(r.sent());
  check(MPI_Alltoallv(answers.data(), r.recv_counts.data(), r.recv_displs.data(), MPI_UINT64_T,
                      replies.data(), r.counts.data(), r.displs.data(), MPI_UINT64_T, comm_),
        "MPI_Alltoallv");
  std::vector<std::uint64_t> rows(ids.size(), kMissing);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (r.slot[i] != std::string::npos) rows[i] = replies[r.slot[i]];
  }
  return rows;
}

std::vector<std::uint64_t> IdRows::rows(const std::vector<std::int64_t>& ids) const {
  std::vector<std::uint64_t> out;
  if (dense_ || total_ == 0) {
    out.resize(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const std::uint64_t row =
          static_cast<std::uint64_t>(ids[i]) - static_cast<std::uint64_t>(min_);
      out[i] = row < total_ ? row : kMissing;
    }
  } else {
    out = ask_owners(ids);
  }
  // One reduction for both checks: strangers found, particles held.
  const std::uint64_t local[2] = {
      std::find(out.begin(), out.end(), kMissing) != out.end() ? 1u : 0u, ids.size()};
  std::uint64_t all[2] = {0, 0};
  check(MPI_Allreduce(local, all, 2, MPI_UINT64_T, MPI_SUM, comm_), "MPI_Allreduce");
  if (all[0] != 0) throw Error("a particle id is not among the file's particles");
  if (all[1] != total_) {
    throw Error(fmt::format("the ranks hold {} particles, the file has {}", all[1], total_));
  }
  return out;
}

}  // namespace pbms::mpi
