// Moves material points to the rank whose cells hold them, after a step or
// at the start of a run. Collective over the driver's communicator.
#pragma once

#include <mpi.h>

#include "pbms/grid/grid_partition.hpp"
#include "pbms/grid/material_points.hpp"

namespace pbms::mpm {

// Points this rank holds but does not own go to their owners; received
// points are appended. Returns the number of points this rank sent.
size_t migrate_points(MPI_Comm comm, const grid::GridPartition& partition,
                      grid::MaterialPoints& points);

}  // namespace pbms::mpm
