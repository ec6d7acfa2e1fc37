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
