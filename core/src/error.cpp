#include "pbms/error.hpp"

#include <fmt/format.h>

namespace pbms {

std::string ConfigError::format() const {
  std::string where = file.empty() ? "<input>" : file;
  if (line > 0) where += fmt::format(":{}:{}", line, column);
  const std::string key = key_path.empty() ? std::string("<document>") : key_path;
  return fmt::format("{}: {}: {}: {}", where, warning ? "warning" : "error", key, message);
}

}  // namespace pbms
