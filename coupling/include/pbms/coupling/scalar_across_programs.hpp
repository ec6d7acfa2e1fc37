// One number each way between two programs' roots, then shared inside
// each program: the two sides' parts of a quantity that spans the
// interface (its opening), sampled together.
#pragma once

#include <mpi.h>

#include <array>
#include <cstddef>
#include <span>

namespace pbms::coupling {

// Collective over both programs: every rank passes its program's values
// (rank 0's are sent) and gets the other program's, as many as it sent.
void swap_values(MPI_Comm inter, MPI_Comm local, std::span<const double> mine,
                 std::span<double> theirs);

template <std::size_t N>
[[nodiscard]] std::array<double, N> swap_values(MPI_Comm inter, MPI_Comm local,
                                                const std::array<double, N>& mine) {
  std::array<double, N> theirs{};
  swap_values(inter, local, mine, theirs);
  return theirs;
}

// Collective over both programs: every rank passes its program's value
// (rank 0's is sent) and gets the other program's.
[[nodiscard]] double swap_scalar(MPI_Comm inter, MPI_Comm local, double mine);

// Collective over both programs: whether either program's rank 0 passed
// true (a decision both must take at the same step).
[[nodiscard]] bool either_program(MPI_Comm inter, MPI_Comm local, bool mine);

}  // namespace pbms::coupling
