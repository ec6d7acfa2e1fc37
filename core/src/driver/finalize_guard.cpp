// Linked into driver executables as an object file (never from an archive,
// where the linker might skip it) and exported, so that a shared library's
// call to MPI_Finalize lands here. PBMS itself finalizes through
// PMPI_Finalize, so any call that arrives here is a library giving up.
#include <mpi.h>

#include <chrono>
#include <string>
#include <thread>

#include "pbms/driver/stage_kind.hpp"

namespace pbms {
std::string describe_unexpected_finalize();
}

extern "C" int MPI_Finalize(void) {
  int rank = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  // Rank 0 usually holds the library's message; let it report first.
  if (rank != 0) std::this_thread::sleep_for(std::chrono::seconds(1));
  pbms::abort_job(pbms::describe_unexpected_finalize());
}
