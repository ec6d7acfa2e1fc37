// The one hand-over at the start of a concurrent stage: the program that
// builds the body (dpd_driver: lattice fill or an earlier stage's final
// state, which only it holds) gives the other program the particles its
// regions assign to it, with a small header (group names, the band, the
// pair reach) as YAML. Root to root over the intercommunicator, then a
// broadcast inside the receiving program; once per stage, not per step.
#pragma once

#include <mpi.h>

#include <string>
#include <vector>

namespace pbms::coupling {

struct Handover {
  std::string header;        // YAML
  std::vector<double> rows;  // `width` doubles a particle
};

// Every rank of the giving program calls it; rank 0's data is sent.
void hand_over(MPI_Comm inter, MPI_Comm local, const Handover& body);
// Every rank of the taking program calls it and gets the same data.
[[nodiscard]] Handover take_over(MPI_Comm inter, MPI_Comm local);

}  // namespace pbms::coupling
