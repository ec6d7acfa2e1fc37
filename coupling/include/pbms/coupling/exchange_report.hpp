// The exchange profile of one program's part of a concurrent stage, per
// rank, into its results: what each rank sent and received across the
// programs (the nodal sums and the partners with their reactions), in how
// many messages, and how long it spent packing and waiting. What a user
// reads to see where a split run spends its coupling time.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <string>

#include "pbms/coupling/nodal_sum_across_programs.hpp"
#include "pbms/results.hpp"

namespace pbms::coupling {

// Collective over `comm` (one program's ranks); rank 0 adds to `r`: table
// `<prefix>_exchange`, one row per rank, and the scalars
// `<prefix>_exchange_bytes_per_step` (sent and received, all ranks),
// `<prefix>_exchange_messages_per_step` (sent, all ranks) and
// `<prefix>_exchange_waiting_fraction` (the most any rank waited, over
// the stage's stepping time).
void report_exchanges(StageResults& r, MPI_Comm comm, const std::string& prefix,
                      const ExchangeProfile& nodal, const ExchangeProfile& partners,
                      std::int64_t steps, double stepping_seconds);

}  // namespace pbms::coupling
