#include "pbms/coupling/scalar_across_programs.hpp"

#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {

void swap_values(MPI_Comm inter, MPI_Comm local, std::span<const double> mine,
                 std::span<double> theirs) {
  int rank = 0;
  MPI_Comm_rank(local, &rank);
  const auto n = static_cast<int>(mine.size());
  if (rank == 0) {
    mpi::check(MPI_Sendrecv(mine.data(), n, MPI_DOUBLE, 0, 420, theirs.data(), n, MPI_DOUBLE, 0,
                            420, inter, MPI_STATUS_IGNORE),
               "MPI_Sendrecv (values across programs)");
  }
  mpi::check(MPI_Bcast(theirs.data(), n, MPI_DOUBLE, 0, local),
             "MPI_Bcast (values across programs)");
}

double swap_scalar(MPI_Comm inter, MPI_Comm local, double mine) {
  double theirs = 0.0;
  swap_values(inter, local, {&mine, 1}, {&theirs, 1});
  return theirs;
}

bool either_program(MPI_Comm inter, MPI_Comm local, bool mine) {
  return swap_scalar(inter, local, mine ? 1.0 : 0.0) > 0.0 || mine;
}

}  // namespace pbms::coupling
