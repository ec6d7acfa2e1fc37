// Error types shared by every PBMS program.
#pragma once

#include <stdexcept>
#include <string>

namespace pbms {

// Anything PBMS reports to a user as a failure. The message is already
// phrased for a person; callers add context (program, rank, stage, step).
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A problem in a user's input file, located precisely enough to be fixed
// without reading the source: file, 1-based line and column, key path.
struct ConfigError {
  std::string file;
  int line = 0;    // 1-based; 0 when unknown
  int column = 0;  // 1-based; 0 when unknown
  std::string key_path;
  std::string message;

  // "file:line:col: error: key.path: message" -- one line, grep-able.
  [[nodiscard]] std::string format() const;
};

}  // namespace pbms
