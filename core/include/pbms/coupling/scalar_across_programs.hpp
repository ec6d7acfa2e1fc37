// One number each way between two programs' roots, then shared inside
// each program: the two sides' parts of a quantity that spans the
// interface (its opening), sampled together.
#pragma once

#include <mpi.h>

namespace pbms::coupling {

// Collective over both programs: every rank passes its program's value
// (rank 0's is sent) and gets the other program's.
[[nodiscard]] double swap_scalar(MPI_Comm inter, MPI_Comm local, double mine);

}  // namespace pbms::coupling
