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

// Keys (ids, rows) sent to the ranks that own them, and the way back for
// the answers.
template <class T>
struct Routed {
  std::vector<T> received;
  std::vector<int> counts, displs, recv_counts, recv_displs;
  std::vector<std::size_t> slot;  // each id's place in the send order; npos: not sent
  [[nodiscard]] std::size_t sent() const {
    return static_cast<std::size_t>(displs.back() + counts.back());
  }
};

// `owner` says -1 for a key no rank owns; that key is not sent.
template <class T, class Owner>
Routed<T> send_to_owners(MPI_Comm comm, MPI_Datatype type, const std::vector<T>& keys,
                         Owner owner) {
  int size = 1;
  check(MPI_Comm_size(comm, &size), "MPI_Comm_size");
  Routed<T> r;
  r.counts.assign(static_cast<std::size_t>(size), 0);
  std::vector<int> to(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    to[i] = owner(keys[i]);
    if (to[i] >= 0) ++r.counts[static_cast<std::size_t>(to[i])];
  }
  r.displs = displacements(r.counts);
  auto at = r.displs;
  std::vector<T> send(r.sent());
  r.slot.assign(keys.size(), std::string::npos);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (to[i] < 0) continue;
    r.slot[i] = static_cast<std::size_t>(at[static_cast<std::size_t>(to[i])]++);
    send[r.slot[i]] = keys[i];
  }
  r.recv_counts.resize(r.counts.size());
  check(MPI_Alltoall(r.counts.data(), 1, MPI_INT, r.recv_counts.data(), 1, MPI_INT, comm),
        "MPI_Alltoall");
  r.recv_displs = displacements(r.recv_counts);
  r.received.resize(static_cast<std::size_t>(r.recv_displs.back() + r.recv_counts.back()));
  check(MPI_Alltoallv(send.data(), r.counts.data(), r.displs.data(), type, r.received.data(),
                      r.recv_counts.data(), r.recv_displs.data(), type, comm),
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
  slice_ =
      send_to_owners(comm, MPI_INT64_T, ids, [&](std::int64_t id) { return owner(id); }).received;
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
  const auto r =
      send_to_owners(comm_, MPI_INT64_T, ids, [&](std::int64_t id) { return owner(id); });
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

namespace pbms::mpi {

RowBlocks::RowBlocks(MPI_Comm comm, std::uint64_t rows) : comm_(comm) {
  int rank = 0, size = 1;
  check(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank");
  check(MPI_Comm_size(comm, &size), "MPI_Comm_size");
  block_ = std::max<std::uint64_t>(
      1, (rows + static_cast<std::uint64_t>(size) - 1) / static_cast<std::uint64_t>(size));
  begin_ = std::min(rows, static_cast<std::uint64_t>(rank) * block_);
  end_ = std::min(rows, begin_ + block_);
}

void RowBlocks::route(const std::vector<std::uint64_t>& rows) {
  auto r = send_to_owners(comm_, MPI_UINT64_T, rows,
                          [&](std::uint64_t row) { return static_cast<int>(row / block_); });
  order_.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) order_[r.slot[i]] = i;
  counts_ = std::move(r.counts);
  displs_ = std::move(r.displs);
  recv_counts_ = std::move(r.recv_counts);
  recv_displs_ = std::move(r.recv_displs);
  arrived_ = std::move(r.received);
}

template <class T>
std::vector<T> RowBlocks::move(const T* values, std::size_t width, MPI_Datatype type) const {
  std::vector<T> send;
  send.reserve(order_.size() * width);
  for (const std::size_t i : order_)
    send.insert(send.end(), values + i * width, values + (i + 1) * width);
  const int w = static_cast<int>(width);
  auto scaled = [w](std::vector<int> v) {
    for (int& x : v) x *= w;
    return v;
  };
  std::vector<T> received(arrived_.size() * width);
  check(MPI_Alltoallv(send.data(), scaled(counts_).data(), scaled(displs_).data(), type,
                      received.data(), scaled(recv_counts_).data(), scaled(recv_displs_).data(),
                      type, comm_),
        "MPI_Alltoallv");
  std::vector<T> block(count() * width);
  for (std::size_t k = 0; k < arrived_.size(); ++k) {
    std::copy_n(received.begin() + static_cast<std::ptrdiff_t>(k * width), width,
                block.begin() + static_cast<std::ptrdiff_t>((arrived_[k] - begin_) * width));
  }
  return block;
}

std::vector<double> RowBlocks::to_block(const double* values, std::size_t width) const {
  return move(values, width, MPI_DOUBLE);
}
std::vector<std::int64_t> RowBlocks::to_block(const std::int64_t* values) const {
  return move(values, 1, MPI_INT64_T);
}
std::vector<int> RowBlocks::to_block(const int* values) const {
  return move(values, 1, MPI_INT);
}

}  // namespace pbms::mpi
