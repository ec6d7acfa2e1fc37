#include "capabilities.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

namespace pbms::coupler {

std::vector<std::string> check_capabilities(const std::vector<config::StageConfig>& stages,
                                            const std::vector<protocol::Hello>& hellos,
                                            const std::vector<int>& sizes) {
  std::vector<std::string> problems;
  std::set<std::string> seen;
  for (size_t i = 0; i < hellos.size(); ++i) {
    const auto& h = hellos[i];
    if (!seen.insert(h.program).second) {
      problems.push_back(fmt::format("two programs in this job call themselves '{}'", h.program));
    }
    if (h.protocol_version != protocol::kProtocolVersion) {
      problems.push_back(fmt::format("{} speaks protocol version {}, the coupler {}", h.program,
                                     h.protocol_version, protocol::kProtocolVersion));
    }
    if (i < sizes.size() && h.ranks != sizes[i]) {
      problems.push_back(
          fmt::format("{} reports {} ranks but runs on {}", h.program, h.ranks, sizes[i]));
    }
  }
  for (const auto& s : stages) {
    if (s.program == config::kCouplerProgram) {
      // The coupler runs it; the drivers it sends requests to must be here.
      for (const auto& d : s.drivers) {
        const bool present = std::any_of(hellos.begin(), hellos.end(),
                                         [&](const protocol::Hello& h) { return h.program == d; });
        if (!present) {
          problems.push_back(
              fmt::format("stage '{}' needs {}, which is not part of this job", s.name, d));
        }
      }
      continue;
    }
    const auto it = std::find_if(hellos.begin(), hellos.end(),
                                 [&](const protocol::Hello& h) { return h.program == s.program; });
    if (it == hellos.end()) {
      problems.push_back(
          fmt::format("stage '{}' needs {}, which is not part of this job", s.name, s.program));
      continue;
    }
    if (std::find(it->capabilities.begin(), it->capabilities.end(), s.kind) ==
        it->capabilities.end()) {
      problems.push_back(
          fmt::format("stage '{}' asks {} for kind '{}', which it does not "
                      "declare (it declares: {})",
                      s.name, s.program, s.kind, fmt::join(it->capabilities, ", ")));
    }
  }
  return problems;
}

}  // namespace pbms::coupler
