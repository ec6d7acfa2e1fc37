// Results of reference stages (the kinds a driver declares cacheable: MD),
// kept across runs in <output>/.cache/ so that a refit or a rerun under a new
// name costs no MD time. An entry is found by the full text of what
// determines the result: stage name and kind, resolved parameters, the
// materials it names, the seed, the driver's software versions and a digest
// of the driver program. The cache lives beside the run directories, so no
// overwrite or rerun of a run removes it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pbms/protocol/messages.hpp"

namespace pbms::coupler {

class ResultCache {
 public:
  explicit ResultCache(std::filesystem::path dir) : dir_(std::move(dir)) {}

  // The stage's answer from an earlier run, with the files it wrote copied
  // into `run_dir`; nothing if no entry has exactly this identity.
  [[nodiscard]] std::optional<protocol::StageDone> find(const std::string& identity,
                                                        const std::filesystem::path& run_dir) const;
  // Stores an answer and the files the stage wrote (its directory in
  // `run_dir` and the files its results list). The entry appears whole or
  // not at all: it is written aside and renamed.
  void store(const std::string& identity, const protocol::StageDone& done,
             const std::filesystem::path& run_dir) const;

  [[nodiscard]] std::filesystem::path entry_dir(const std::string& identity) const;

 private:
  std::filesystem::path dir_;
};

// 64-bit FNV-1a of a file's bytes, as 16 hex digits ("" if it cannot be read).
std::string file_digest(const std::filesystem::path& file);

// The identity text of a request whose materials block holds only the
// materials it names; `input_files` are "path: digest" lines of the files
// those materials read (a potential edited in place is another material).
std::string cache_identity(const protocol::RunStage& request,
                           const std::vector<std::string>& software,
                           const std::string& driver_digest,
                           const std::vector<std::string>& input_files);

}  // namespace pbms::coupler
