#include "pbms/mpi/rank_rows.hpp"

#include "pbms/mpi/comm.hpp"

namespace pbms::mpi {

RankRows gather_rank_rows(MPI_Comm comm, const std::vector<double>& mine, std::size_t width) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks)), offsets(counts.size());
  check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm), "MPI_Gather");
  RankRows out;
  int total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = total;
    total += counts[r];
    out.counts.push_back(static_cast<double>(static_cast<std::size_t>(counts[r]) / width));
  }
  out.rows.resize(rank == 0 ? static_cast<std::size_t>(total) : 0);
  check(MPI_Gatherv(mine.data(), count, MPI_DOUBLE, out.rows.data(), counts.data(), offsets.data(),
                    MPI_DOUBLE, 0, comm),
        "MPI_Gatherv");
  return out;
}

}  // namespace pbms::mpi
