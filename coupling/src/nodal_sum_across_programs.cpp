#include "pbms/coupling/nodal_sum_across_programs.hpp"

#include "pbms/grid/for_each_node.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {
namespace {

constexpr int kNodalSumTag = 300;

// Consecutive transfers with the same peer (the plan lists each peer's
// blocks together, images in a fixed order on both sides).
std::vector<PeerRange> by_peer(const std::vector<NodeTransfer>& t) {
  std::vector<PeerRange> out;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (out.empty() || out.back().peer != t[i].peer) out.push_back({t[i].peer, i, i});
    out.back().end = i + 1;
  }
  return out;
}

}  // namespace

NodalSumAcrossPrograms::NodalSumAcrossPrograms(MPI_Comm inter, const grid::GridPartition& mine,
                                               const grid::GridPartition& theirs,
                                               const grid::NodeBox& band)
    : inter_(inter), cells_(mine.grid().cells()) {
  int rank = 0;
  mpi::check(MPI_Comm_rank(inter, &rank), "MPI_Comm_rank");
  local_ = mine.nodes_of(rank);
  receives_ = receives_of(mine, rank, theirs, band);
  sends_ = sends_of(mine, rank, theirs, band);
  send_peers_ = by_peer(sends_);
  recv_peers_ = by_peer(receives_);
  send_buf_.resize(send_peers_.size());
  recv_buf_.resize(recv_peers_.size());
}

void NodalSumAcrossPrograms::sum(double* data, int components, int stride) {
  transfer(data, data, components, stride);
}

void NodalSumAcrossPrograms::copy_across(const double* from, double* to, int components,
                                         int stride) {
  const auto n = static_cast<size_t>(local_.count());
  for (size_t k = 0; k < n; ++k) {
    for (int c = 0; c < components; ++c) to[k * static_cast<size_t>(stride) + c] = 0.0;
  }
  transfer(from, to, components, stride);
}

// One message per peer and direction: a peer's blocks (one per periodic
// image) travel packed together.
void NodalSumAcrossPrograms::transfer(const double* from, double* to, int components, int stride) {
  const double start = MPI_Wtime();
  const auto nc = static_cast<size_t>(components);
  const auto ns = static_cast<size_t>(stride);
  requests_.assign(send_peers_.size() + recv_peers_.size(), MPI_REQUEST_NULL);
  for (size_t r = 0; r < recv_peers_.size(); ++r) {
    std::int64_t nodes = 0;
    for (size_t b = recv_peers_[r].begin; b < recv_peers_[r].end; ++b)
      nodes += receives_[b].nodes.count();
    auto& buf = recv_buf_[r];
    buf.resize(static_cast<size_t>(nodes) * nc);
    mpi::check(MPI_Irecv(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, recv_peers_[r].peer,
                         kNodalSumTag, inter_, &requests_[r]),
               "MPI_Irecv (nodal sum across programs)");
  }
  // Every block is packed before anything is added, so each side sends
  // only its own part.
  for (size_t p = 0; p < send_peers_.size(); ++p) {
    auto& buf = send_buf_[p];
    buf.clear();
    for (size_t b = send_peers_[p].begin; b < send_peers_[p].end; ++b) {
      const NodeTransfer& t = sends_[b];
      grid::for_each_node(t.nodes, [&](std::array<int, 3> ijk) {
        for (size_t a = 0; a < 3; ++a) ijk[a] -= t.shift[a] * cells_[a];
        const double* d = from + static_cast<size_t>(local_.local_index(ijk)) * ns;
        buf.insert(buf.end(), d, d + nc);
      });
    }
    mpi::check(MPI_Isend(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, send_peers_[p].peer,
                         kNodalSumTag, inter_, &requests_[recv_peers_.size() + p]),
               "MPI_Isend (nodal sum across programs)");
    profile_.bytes_sent += static_cast<std::int64_t>(buf.size() * sizeof(double));
  }
  profile_.messages_sent += static_cast<std::int64_t>(send_peers_.size());
  const double posted = MPI_Wtime();
  mpi::check(MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE),
             "MPI_Waitall (nodal sum across programs)");
  const double arrived = MPI_Wtime();
  for (size_t r = 0; r < recv_peers_.size(); ++r) {
    const double* in = recv_buf_[r].data();
    for (size_t b = recv_peers_[r].begin; b < recv_peers_[r].end; ++b) {
      grid::for_each_node(receives_[b].nodes, [&](const std::array<int, 3>& ijk) {
        double* d = to + static_cast<size_t>(local_.local_index(ijk)) * ns;
        for (size_t c = 0; c < nc; ++c) d[c] += *in++;
      });
    }
    profile_.bytes_received += static_cast<std::int64_t>(recv_buf_[r].size() * sizeof(double));
  }
  ++profile_.exchanges;
  profile_.seconds_waiting += arrived - posted;
  profile_.seconds_packing += (posted - start) + (MPI_Wtime() - arrived);
}

}  // namespace pbms::coupling
