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

// A stage that cannot give a result for the inputs it was sent (a candidate
// potential whose crystal melts, a NaN), thrown on every rank of the stage's
// group at once. The driver answers StageFailed and stays in service, so a
// fit can go on to the next candidate. Any other exception ends the job.
class StageFailure : public Error {
 public:
  using Error::Error;
};

// A problem in a user's input file, located precisely enough to be fixed
// without reading the source: file, 1-based line and column, key path.
struct ConfigError {
  std::string file;
  int line = 0;    // 1-based; 0 when unknown
  int column = 0;  // 1-based; 0 when unknown
  std::string key_path;
  std::string message;
  // A legal but suspicious value: printed as "warning:", it stops nothing.
  bool warning = false;

  // "file:line:col: error: key.path: message" -- one line, grep-able.
  [[nodiscard]] std::string format() const;
};

}  // namespace pbms
