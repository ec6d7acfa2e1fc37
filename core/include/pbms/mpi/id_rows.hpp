// The row of each particle in a file whose rows are all particles in
// ascending id, found by whichever rank holds the particle now. Particles
// migrate between ranks, so a rank cannot keep its rows from the frame
// before; and no rank may hold every id (that is the gather collective
// output exists to avoid). Ids that are one dense range map to rows by
// arithmetic; other id sets are split by id range over the ranks, each
// rank keeping its range's ids sorted, and rows are asked of the owner.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <vector>

namespace pbms::mpi {

class IdRows {
 public:
  // Collective. `ids`: this rank's share of the set, in any order; every id
  // appears on exactly one rank. Throws on every rank on a repeated id.
  IdRows(MPI_Comm comm, const std::vector<std::int64_t>& ids);

  // Collective: every rank passes the ids it holds now (any order). Throws on
  // every rank when an id is not in the set or the ranks together do not
  // hold the whole set once, so that no rank goes on to a collective write
  // alone.
  [[nodiscard]] std::vector<std::uint64_t> rows(const std::vector<std::int64_t>& ids) const;
  [[nodiscard]] std::uint64_t total() const { return total_; }
  [[nodiscard]] bool dense() const { return dense_; }

 private:
  [[nodiscard]] int owner(std::int64_t id) const;
  // The ranks that own `ids` answer with their rows; kMissing for an id the
  // owner does not have.
  [[nodiscard]] std::vector<std::uint64_t> ask_owners(const std::vector<std::int64_t>& ids) const;

  MPI_Comm comm_;
  int size_ = 1;
  std::int64_t min_ = 0;
  std::uint64_t total_ = 0;
  std::uint64_t bucket_ = 1;  // ids per owner's range
  bool dense_ = true;
  std::vector<std::int64_t> slice_;  // the owned range's ids, sorted
  std::uint64_t slice_row0_ = 0;
};

}  // namespace pbms::mpi

namespace pbms::mpi {

// The rows 0..n-1 of a file cut into one block per rank, in rank order, and
// the exchange that brings each particle's values to the rank whose block
// holds its row. A block is one hyperslab, written in one piece. Writing
// each rank's own scattered rows (an HDF5 point selection) measured 3 to 6
// times slower than gathering everything on rank 0 (bench/h5md_write.sh),
// as MPI-IO takes every 8-byte element as a piece of its own; and HDF5 1.10
// builds a union of hyperslab runs in quadratic time (40 s for 25,000).
class RowBlocks {
 public:
  RowBlocks(MPI_Comm comm, std::uint64_t rows);
  [[nodiscard]] std::uint64_t begin() const { return begin_; }
  [[nodiscard]] std::uint64_t count() const { return end_ - begin_; }

  // Collective: the rows of this rank's particles (any order) for the
  // to_block() calls that follow.
  void route(const std::vector<std::uint64_t>& rows);
  // Collective: `width` values per particle, in the order given to route(),
  // returned as this rank's block, `width` values per row, in row order.
  [[nodiscard]] std::vector<double> to_block(const double* values, std::size_t width) const;
  [[nodiscard]] std::vector<std::int64_t> to_block(const std::int64_t* values) const;
  [[nodiscard]] std::vector<int> to_block(const int* values) const;

 private:
  template <class T>
  std::vector<T> move(const T* values, std::size_t width, MPI_Datatype type) const;

  MPI_Comm comm_;
  std::uint64_t block_ = 1, begin_ = 0, end_ = 0;
  std::vector<std::size_t> order_;  // particles grouped by the rank they go to
  std::vector<int> counts_, displs_, recv_counts_, recv_displs_;  // particles
  std::vector<std::uint64_t> arrived_;                            // rows received, in arrival order
};

}  // namespace pbms::mpi
