// Completes nodal sums on an MPM grid split by a GridPartition: after each
// rank has scattered its own points to its nodes, the nodes it shares with
// neighbouring boxes (and with periodic images) hold partial sums; sum()
// adds the other parts so every copy of a node holds the whole sum.
#pragma once

#include <mpi.h>

#include <vector>

#include "pbms/grid/grid_partition.hpp"

namespace pbms::mpi {

class HaloSum {
 public:
  // Collective-free: every rank builds its own exchange list from the
  // partition. `comm` must have partition.ranks() ranks and outlive this.
  HaloSum(MPI_Comm comm, const grid::GridPartition& partition);

  // `data` holds, per node of this rank's nodes_of() box (i fastest), a
  // record of `stride` doubles whose first `components` are summed.
  // Blocking; all ranks call it together.
  void sum(double* data, int components, int stride);

  [[nodiscard]] bool empty() const { return overlaps_.empty(); }

 private:
  MPI_Comm comm_;
  grid::NodeBox local_;
  std::vector<grid::NodeOverlap> overlaps_;
  std::vector<std::vector<double>> send_, recv_;
  std::vector<MPI_Request> requests_;
};

}  // namespace pbms::mpi
