// Every rank's rows of `width` doubles gathered on rank 0 in rank order,
// each rank's in the order it holds them, with how many rows each rank
// gave: what a checkpoint keeps so that a resume on as many ranks gives
// every rank back its own rows in their order.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <vector>

namespace pbms::mpi {

struct RankRows {
  std::vector<double> rows;    // rank 0 only; empty elsewhere
  std::vector<double> counts;  // rows per rank (rank 0 only)
};

// Collective over `comm`.
[[nodiscard]] RankRows gather_rank_rows(MPI_Comm comm, const std::vector<double>& mine,
                                        std::size_t width);

}  // namespace pbms::mpi
