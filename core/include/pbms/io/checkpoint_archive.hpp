// A stage's state at a checkpoint: named arrays of doubles (ids, positions,
// sample series, counters), the same on every rank once read. A component
// with state adds its arrays under its own prefix and takes them back on
// resume; the file is one HDF5 dataset per name.
#pragma once

#include <mpi.h>

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
  // Throws pbms::Error naming the checkpoint's file and the missing entry.
  [[nodiscard]] const std::vector<double>& get(const std::string& name) const;
  [[nodiscard]] double scalar(const std::string& name) const { return get(name).at(0); }
  [[nodiscard]] bool has(const std::string& name) const { return arrays_.count(name) != 0; }

  // Writes every array to `file` (one process), through a temporary name
  // renamed into place when the file is complete and flushed, so that a
  // kill leaves either the whole file or none. PBMS_TEST_CHECKPOINT_PAUSE
  // ("NAME:SECONDS") holds the writer of a file whose name holds NAME that
  // long between the two: the tests' window for a kill mid-write.
  // `identity` says whose state it is: parts separated by "; ", such as the
  // stage and its parameters, then the version that wrote it.
  void write(const std::filesystem::path& file, const std::string& identity) const;
  // Reads `file` on rank 0 and hands it to every rank of `comm`. Throws
  // pbms::Error when the file cannot be read or its identity is not
  // `identity` (another stage, config or version), saying which differs.
  static CheckpointArchive read(const std::filesystem::path& file, const std::string& identity,
                                MPI_Comm comm);

 private:
  std::filesystem::path source_;
  std::map<std::string, std::vector<double>> arrays_;
};

}  // namespace pbms
