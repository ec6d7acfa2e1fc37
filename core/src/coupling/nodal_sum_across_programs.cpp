#include "pbms/coupling/nodal_sum_across_programs.hpp"

#include "pbms/grid/for_each_node.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {
namespace {

// Several blocks between one pair of ranks (periodic images) are told
// apart by their shift, as a base-3 number.
int tag_of(const std::array<int, 3>& s) {
  return 300 + (s[0] + 1) + 3 * (s[1] + 1) + 9 * (s[2] + 1);
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
  send_buf_.resize(sends_.size());
  recv_buf_.resize(receives_.size());
}

void NodalSumAcrossPrograms::sum(double* data, int components, int stride) {
  const double start = MPI_Wtime();
  const auto nc = static_cast<size_t>(components);
  const auto ns = static_cast<size_t>(stride);
  requests_.assign(sends_.size() + receives_.size(), MPI_REQUEST_NULL);
  for (size_t r = 0; r < receives_.size(); ++r) {
    auto& buf = recv_buf_[r];
    buf.resize(static_cast<size_t>(receives_[r].nodes.count()) * nc);
    mpi::check(MPI_Irecv(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, receives_[r].peer,
                         tag_of(receives_[r].shift), inter_, &requests_[r]),
               "MPI_Irecv (nodal sum across programs)");
  }
  // Every block is packed before anything is added, so each side sends
  // only its own part.
  for (size_t s = 0; s < sends_.size(); ++s) {
    const NodeTransfer& t = sends_[s];
    auto& buf = send_buf_[s];
    buf.clear();
    grid::for_each_node(t.nodes, [&](std::array<int, 3> ijk) {
      for (size_t a = 0; a < 3; ++a) ijk[a] -= t.shift[a] * cells_[a];
      const double* d = data + static_cast<size_t>(local_.local_index(ijk)) * ns;
      buf.insert(buf.end(), d, d + nc);
    });
    mpi::check(MPI_Isend(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, t.peer,
                         tag_of(t.shift), inter_, &requests_[receives_.size() + s]),
               "MPI_Isend (nodal sum across programs)");
    profile_.bytes_sent += static_cast<std::int64_t>(buf.size() * sizeof(double));
  }
  profile_.messages_sent += static_cast<std::int64_t>(sends_.size());
  const double posted = MPI_Wtime();
  mpi::check(MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE),
             "MPI_Waitall (nodal sum across programs)");
  const double arrived = MPI_Wtime();
  for (size_t r = 0; r < receives_.size(); ++r) {
    const double* in = recv_buf_[r].data();
    grid::for_each_node(receives_[r].nodes, [&](const std::array<int, 3>& ijk) {
      double* d = data + static_cast<size_t>(local_.local_index(ijk)) * ns;
      for (size_t c = 0; c < nc; ++c) d[c] += *in++;
    });
    profile_.bytes_received += static_cast<std::int64_t>(recv_buf_[r].size() * sizeof(double));
  }
  ++profile_.exchanges;
  profile_.seconds_waiting += arrived - posted;
  profile_.seconds_packing += (posted - start) + (MPI_Wtime() - arrived);
}

}  // namespace pbms::coupling
