#include "pbms/coupling/body_handover.hpp"

#include <cstdint>

#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {
namespace {

constexpr int kSizesTag = 410;
constexpr int kHeaderTag = 411;
constexpr int kRowsTag = 412;

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

}  // namespace

void hand_over(MPI_Comm inter, MPI_Comm /*local*/, const Handover& body) {
  if (rank_of(inter) != 0) return;
  const std::int64_t sizes[2] = {static_cast<std::int64_t>(body.header.size()),
                                 static_cast<std::int64_t>(body.rows.size())};
  mpi::check(MPI_Send(sizes, 2, MPI_INT64_T, 0, kSizesTag, inter), "MPI_Send (hand-over)");
  mpi::check(
      MPI_Send(body.header.data(), static_cast<int>(sizes[0]), MPI_CHAR, 0, kHeaderTag, inter),
      "MPI_Send (hand-over header)");
  mpi::check(MPI_Send(body.rows.data(), static_cast<int>(sizes[1]), MPI_DOUBLE, 0, kRowsTag, inter),
             "MPI_Send (hand-over rows)");
}

Handover take_over(MPI_Comm inter, MPI_Comm local) {
  std::int64_t sizes[2] = {0, 0};
  const bool root = rank_of(local) == 0;
  if (root) {
    mpi::check(MPI_Recv(sizes, 2, MPI_INT64_T, 0, kSizesTag, inter, MPI_STATUS_IGNORE),
               "MPI_Recv (hand-over)");
  }
  mpi::check(MPI_Bcast(sizes, 2, MPI_INT64_T, 0, local), "MPI_Bcast (hand-over)");
  Handover h;
  h.header.resize(static_cast<std::size_t>(sizes[0]));
  h.rows.resize(static_cast<std::size_t>(sizes[1]));
  if (root) {
    mpi::check(MPI_Recv(h.header.data(), static_cast<int>(sizes[0]), MPI_CHAR, 0, kHeaderTag, inter,
                        MPI_STATUS_IGNORE),
               "MPI_Recv (hand-over header)");
    mpi::check(MPI_Recv(h.rows.data(), static_cast<int>(sizes[1]), MPI_DOUBLE, 0, kRowsTag, inter,
                        MPI_STATUS_IGNORE),
               "MPI_Recv (hand-over rows)");
  }
  mpi::check(MPI_Bcast(h.header.data(), static_cast<int>(sizes[0]), MPI_CHAR, 0, local),
             "MPI_Bcast (hand-over header)");
  mpi::check(MPI_Bcast(h.rows.data(), static_cast<int>(sizes[1]), MPI_DOUBLE, 0, local),
             "MPI_Bcast (hand-over rows)");
  return h;
}

}  // namespace pbms::coupling
