// Every rank's rows of `width` doubles, gathered on rank 0 and sorted by
// their first value (a global id), so that what rank 0 analyses or writes
// does not depend on the decomposition. For small sets (a bar's profile);
// empty on the other ranks.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <vector>

namespace pbms::mpm {

[[nodiscard]] std::vector<double> rows_on_rank_zero(MPI_Comm comm, const std::vector<double>& local,
                                                    std::size_t width);

}  // namespace pbms::mpm
