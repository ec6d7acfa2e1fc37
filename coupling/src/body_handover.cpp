#include "pbms/coupling/body_handover.hpp"

#include <cstddef>
#include <cstdint>

#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {
namespace {

constexpr int kSizeTag = 410;
constexpr int kBytesTag = 411;

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

}  // namespace

void hand_over(MPI_Comm inter, MPI_Comm /*local*/, const BodyHandover& body) {
  if (rank_of(inter) != 0) return;
  protocol::Encoder e;
  e.put(body);
  const std::vector<std::byte> bytes = e.take();
  const auto size = static_cast<std::int64_t>(bytes.size());
  mpi::check(MPI_Send(&size, 1, MPI_INT64_T, 0, kSizeTag, inter), "MPI_Send (hand-over)");
  mpi::check(MPI_Send(bytes.data(), static_cast<int>(size), MPI_BYTE, 0, kBytesTag, inter),
             "MPI_Send (hand-over body)");
}

BodyHandover take_over(MPI_Comm inter, MPI_Comm local) {
  std::int64_t size = 0;
  const bool root = rank_of(local) == 0;
  if (root) {
    mpi::check(MPI_Recv(&size, 1, MPI_INT64_T, 0, kSizeTag, inter, MPI_STATUS_IGNORE),
               "MPI_Recv (hand-over)");
  }
  mpi::check(MPI_Bcast(&size, 1, MPI_INT64_T, 0, local), "MPI_Bcast (hand-over)");
  std::vector<std::byte> bytes(static_cast<std::size_t>(size));
  if (root) {
    mpi::check(MPI_Recv(bytes.data(), static_cast<int>(size), MPI_BYTE, 0, kBytesTag, inter,
                        MPI_STATUS_IGNORE),
               "MPI_Recv (hand-over body)");
  }
  mpi::check(MPI_Bcast(bytes.data(), static_cast<int>(size), MPI_BYTE, 0, local),
             "MPI_Bcast (hand-over body)");
  protocol::Decoder d(bytes.data(), bytes.size());
  BodyHandover body;
  d.get(body);
  return body;
}

}  // namespace pbms::coupling
