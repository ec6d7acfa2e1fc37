#include "pbms/mpi/sorted_rows.hpp"

#include <algorithm>
#include <numeric>

#include "pbms/mpi/comm.hpp"

namespace pbms::mpi {

std::vector<double> sorted_rows(MPI_Comm comm, const std::vector<double>& local, std::size_t width,
                                RowsTo to) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const bool everywhere = to == RowsTo::kEveryRank;
  const int n = static_cast<int>(local.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), displs(counts.size());
  check(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm), "MPI_Allgather");
  int total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    displs[r] = total;
    total += counts[r];
  }
  std::vector<double> all;
  if (everywhere || rank == 0) all.resize(static_cast<std::size_t>(total));
  if (everywhere) {
    check(MPI_Allgatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                         MPI_DOUBLE, comm),
          "MPI_Allgatherv");
  } else {
    check(MPI_Gatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                      MPI_DOUBLE, 0, comm),
          "MPI_Gatherv");
  }
  const std::size_t rows = all.size() / width;
  std::vector<std::size_t> order(rows);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return all[a * width] < all[b * width]; });
  std::vector<double> out;
  out.reserve(all.size());
  for (const std::size_t i : order) {
    const auto first = all.begin() + static_cast<std::ptrdiff_t>(i * width);
    out.insert(out.end(), first, first + static_cast<std::ptrdiff_t>(width));
  }
  return out;
}

}  // namespace pbms::mpi
