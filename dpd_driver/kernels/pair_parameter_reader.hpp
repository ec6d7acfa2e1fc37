// Reads one pair style's parameters. Every refusal is a pbms::Error naming
// the style and the parameter, so a user can fix the input without the source.
#pragma once

#include <set>
#include <string>
#include <string_view>

#include "kernels/pair_style.hpp"

namespace pbms::dpd {

class PairParameterReader {
 public:
  PairParameterReader(std::string_view style, const PairStyleParameters& params);

  // A finite number; missing is an error.
  double required(const std::string& name);
  // A finite number > 0; missing is an error.
  double required_positive(const std::string& name);
  // A finite number, or fallback when absent.
  double optional(const std::string& name, double fallback);
  // 0 (no) or 1 (yes), or fallback when absent.
  bool optional_flag(const std::string& name, bool fallback);
  // A non-empty text such as a file name; missing is an error.
  std::string required_text(const std::string& name);

  // Throws when the parameters hold a name no call above asked for (a typo).
  void reject_unknown() const;

  // Throws a pbms::Error "<style>: <name> <message>".
  [[noreturn]] void fail(const std::string& name, const std::string& message) const;

 private:
  std::string style_;
  const PairStyleParameters& params_;
  std::set<std::string, std::less<>> accepted_;
};

}  // namespace pbms::dpd
