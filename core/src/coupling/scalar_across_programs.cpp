#include "pbms/coupling/scalar_across_programs.hpp"

#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {

double swap_scalar(MPI_Comm inter, MPI_Comm local, double mine) {
  int rank = 0;
  MPI_Comm_rank(local, &rank);
  double theirs = 0.0;
  if (rank == 0) {
    mpi::check(MPI_Sendrecv(&mine, 1, MPI_DOUBLE, 0, 420, &theirs, 1, MPI_DOUBLE, 0, 420, inter,
                            MPI_STATUS_IGNORE),
               "MPI_Sendrecv (scalar across programs)");
  }
  mpi::check(MPI_Bcast(&theirs, 1, MPI_DOUBLE, 0, local), "MPI_Bcast (scalar across programs)");
  return theirs;
}

}  // namespace pbms::coupling
