// A stage's state at a checkpoint: named arrays of doubles (ids, positions,
// sample series, counters), the same on every rank once read. A component
// with state adds its arrays under its own prefix and takes them back on
// resume; the file is one HDF5 dataset per name. Two kinds of array:
// - put(): one array for the whole program, as rank 0 holds it;
// - put_rows(): each rank's own rows (particles, points), written by every
//   rank at its place in parallel HDF5, rank after rank, and read back
//   whole, with how many rows each rank wrote (rank_counts());
// - put_bytes(): a byte string as rank 0 holds it (a file of another
//   program's, such as a LAMMPS restart file, or a script).
#pragma once

#include <hdf5.h>
#include <mpi.h>

#include <cstddef>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pbms {

class CheckpointArchive {
 public:
  void put(const std::string& name, std::vector<double> values);
  void put(const std::string& name, double value) { put(name, std::vector<double>{value}); }
  // This rank's rows of `width` doubles; every rank of the writing
  // communicator puts rows under the same names.
  void put_rows(const std::string& name, std::vector<double> mine, std::size_t width);
  // Throws pbms::Error naming the checkpoint's file and the missing entry.
  [[nodiscard]] const std::vector<double>& get(const std::string& name) const;
  [[nodiscard]] double scalar(const std::string& name) const { return get(name).at(0); }
  [[nodiscard]] bool has(const std::string& name) const { return arrays_.count(name) != 0; }
  void put_bytes(const std::string& name, std::string bytes);
  // Throws pbms::Error as get() does.
  [[nodiscard]] const std::string& bytes(const std::string& name) const;
  // Of an array read back that was written by put_rows(): the rows each
  // rank wrote, in rank order (as doubles, as the engines take them).
  [[nodiscard]] const std::vector<double>& rank_counts(const std::string& name) const {
    return get(name + kRankCountsSuffix);
  }

  // Collective over `comm`: writes every array to `file` in parallel HDF5
  // (MPI-IO; rank 0 writes the put() arrays, every rank its rows), through
  // a temporary name that rank 0 renames into place once the file is
  // complete and closed, so that a kill leaves either the whole file or
  // none. PBMS_TEST_CHECKPOINT_PAUSE
  // ("NAME:SECONDS") holds the writer of a file whose name holds NAME that
  // long between the two: the tests' window for a kill mid-write.
  // `identity` says whose state it is: parts separated by "; ", such as the
  // stage and its parameters, then the version that wrote it.
  void write(const std::filesystem::path& file, const std::string& identity,
             MPI_Comm comm = MPI_COMM_SELF) const;
  // Reads `file` on rank 0 and hands it to every rank of `comm`. Throws
  // pbms::Error when the file cannot be read or its identity is not
  // `identity` (another stage, config or version), saying which differs.
  static CheckpointArchive read(const std::filesystem::path& file, const std::string& identity,
                                MPI_Comm comm);

 private:
  static constexpr const char* kRankCountsSuffix = "#rank_counts";
  struct Rows {
    std::vector<double> mine;
    std::size_t width = 1;
  };
  void write_contents(hid_t file, MPI_Comm comm) const;
  void read_entries(hid_t file);          // rank 0
  void broadcast_entries(MPI_Comm comm);  // rank 0's to every rank

  std::filesystem::path source_;
  std::map<std::string, std::vector<double>> arrays_;
  std::map<std::string, Rows> rows_;
  std::map<std::string, std::string> bytes_;
};

}  // namespace pbms
