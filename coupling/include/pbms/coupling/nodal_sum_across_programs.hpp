// Adds another program's part of the nodal sums on the grid two programs
// share (the DPD and MPM sides of a concurrent run): mass, momentum and
// force after both have mapped their particles, then the remapped
// momentum. Rank to rank over an intercommunicator between the ranks
// whose boxes overlap (CrossProgramNodePlan); never gathered on a root,
// and periodic where the grid is.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <vector>

#include "pbms/coupling/cross_program_node_plan.hpp"

namespace pbms::coupling {

// Bytes and seconds of one side's exchanges so far (the exchange profile).
struct ExchangeProfile {
  std::int64_t exchanges = 0;
  std::int64_t messages_sent = 0;
  std::int64_t bytes_sent = 0;
  std::int64_t bytes_received = 0;
  double seconds_packing = 0.0;  // packing, posting the sends and adding
  double seconds_waiting = 0.0;  // in MPI_Waitall
};

// The transfers [begin, end) of a plan that go to or come from one peer.
struct PeerRange {
  int peer = 0;
  std::size_t begin = 0;
  std::size_t end = 0;
};

class NodalSumAcrossPrograms {
 public:
  // `inter` joins this program's ranks (split by `mine`) to the other
  // program's (split by `theirs`); it must outlive this. Only nodes inside
  // `band` (global node indices) are summed. Collective-free.
  NodalSumAcrossPrograms(MPI_Comm inter, const grid::GridPartition& mine,
                         const grid::GridPartition& theirs, const grid::NodeBox& band);

  // `data` holds, per node of mine.nodes_of(rank) (i fastest), a record of
  // `stride` doubles whose `components` from the first are this program's
  // complete part; on return they are the sum over both programs. Both
  // programs call it together with the same `components`.
  void sum(double* data, int components, int stride);
  // The other program's part alone: on return `to` (laid out as `data`)
  // holds in its `components` from the first the other program's part on
  // the nodes both hold, and zero elsewhere; `from` is this program's part,
  // which the other program receives. Both programs call it together.
  void copy_across(const double* from, double* to, int components, int stride);

  [[nodiscard]] const ExchangeProfile& profile() const { return profile_; }
  [[nodiscard]] const std::vector<NodeTransfer>& receives() const { return receives_; }
  [[nodiscard]] const std::vector<NodeTransfer>& sends() const { return sends_; }

 private:
  // Sends `from`'s components and adds what arrives to `to`'s.
  void transfer(const double* from, double* to, int components, int stride);

  MPI_Comm inter_;
  grid::NodeBox local_;
  std::array<int, 3> cells_{};
  std::vector<NodeTransfer> receives_, sends_;
  std::vector<PeerRange> recv_peers_, send_peers_;
  std::vector<std::vector<double>> send_buf_, recv_buf_;
  std::vector<MPI_Request> requests_;
  ExchangeProfile profile_;
};

}  // namespace pbms::coupling
