// Every rank's rows of `width` doubles, gathered on rank 0 (or on every
// rank) and sorted by their first value (a global id), so that what is
// analysed or written does not depend on the decomposition. For small
// sets (a bar's profile, a final state kept for a later stage); particle
// output at scale is written collectively instead.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <vector>

namespace pbms::mpi {

enum class RowsTo { kRankZero, kEveryRank };

// Empty on the other ranks with RowsTo::kRankZero.
[[nodiscard]] std::vector<double> sorted_rows(MPI_Comm comm, const std::vector<double>& local,
                                              std::size_t width, RowsTo to);

}  // namespace pbms::mpi
