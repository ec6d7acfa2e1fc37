#include "pbms/grid/halo_sum.hpp"

#include "pbms/grid/for_each_node.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::mpi {
namespace {

// Tags tell apart several blocks shared with one rank (two periodic images
// of a two-box axis): the shift as a base-3 number.
int tag_of(const std::array<int, 3>& s) {
  return 100 + (s[0] + 1) + 3 * (s[1] + 1) + 9 * (s[2] + 1);
}

}  // namespace

HaloSum::HaloSum(MPI_Comm comm, const grid::GridPartition& partition) : comm_(comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  local_ = partition.nodes_of(rank);
  overlaps_ = partition.overlaps_of(rank);
  send_.resize(overlaps_.size());
  recv_.resize(overlaps_.size());
}

void HaloSum::sum(double* data, int components, int stride) {
  if (overlaps_.empty()) return;
  const auto nc = static_cast<size_t>(components);
  const auto ns = static_cast<size_t>(stride);
  requests_.assign(2 * overlaps_.size(), MPI_REQUEST_NULL);
  // Pack every outgoing block before adding anything, so each rank sends
  // only its own contributions.
  for (size_t o = 0; o < overlaps_.size(); ++o) {
    const auto& ov = overlaps_[o];
    auto& buf = send_[o];
    buf.clear();
    grid::for_each_node(ov.nodes, [&](const std::array<int, 3>& ijk) {
      const double* d = data + static_cast<size_t>(local_.local_index(ijk)) * ns;
      buf.insert(buf.end(), d, d + nc);
    });
    recv_[o].resize(buf.size());
    const int n = static_cast<int>(buf.size());
    const std::array<int, 3> back{-ov.shift[0], -ov.shift[1], -ov.shift[2]};
    check(
        MPI_Irecv(recv_[o].data(), n, MPI_DOUBLE, ov.rank, tag_of(back), comm_, &requests_[2 * o]),
        "MPI_Irecv (halo)");
    check(MPI_Isend(buf.data(), n, MPI_DOUBLE, ov.rank, tag_of(ov.shift), comm_,
                    &requests_[2 * o + 1]),
          "MPI_Isend (halo)");
  }
  check(MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE),
        "MPI_Waitall (halo)");
  // The peer packed the same block, seen from its side, in the same
  // k, j, i order.
  for (size_t o = 0; o < overlaps_.size(); ++o) {
    const double* r = recv_[o].data();
    grid::for_each_node(overlaps_[o].nodes, [&](const std::array<int, 3>& ijk) {
      double* d = data + static_cast<size_t>(local_.local_index(ijk)) * ns;
      for (size_t c = 0; c < nc; ++c) d[c] += *r++;
    });
  }
}

}  // namespace pbms::mpi
