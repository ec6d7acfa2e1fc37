// This job's ranks split into two groups that play two programs of an
// MPMD job: the first `first_ranks` world ranks are program 0, the rest
// program 1, joined by an intercommunicator (as MpmdWorld::connect gives).
#pragma once

#include <mpi.h>

struct TwoPrograms {
  int program = 0;  // 0 or 1
  int rank = 0;     // in the program
  int ranks[2] = {1, 1};
  MPI_Comm local = MPI_COMM_NULL;
  MPI_Comm inter = MPI_COMM_NULL;

  explicit TwoPrograms(int first_ranks) {
    int world_rank = 0, world_size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &world_size);
    program = world_rank < first_ranks ? 0 : 1;
    ranks[0] = first_ranks;
    ranks[1] = world_size - first_ranks;
    MPI_Comm_split(MPI_COMM_WORLD, program, world_rank, &local);
    MPI_Intercomm_create(local, 0, MPI_COMM_WORLD, program == 0 ? first_ranks : 0, 77, &inter);
    MPI_Comm_rank(local, &rank);
  }
  ~TwoPrograms() {
    MPI_Comm_free(&inter);
    MPI_Comm_free(&local);
  }
  TwoPrograms(const TwoPrograms&) = delete;
  TwoPrograms& operator=(const TwoPrograms&) = delete;
};

// Every split of this job into two non-empty programs.
inline int world_size() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}
