// A checkpoint of a stage that several programs run (a concurrent stage's
// DPD and MPM parts) is complete only once every part has written its file:
// the files reported so far, by step, until the last part's arrives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pbms::coupler {

class PartCheckpoints {
 public:
  explicit PartCheckpoints(std::size_t parts) : parts_(parts) {}

  // Part `part` (0: the main one) wrote `file` after `step`. Returns every
  // part's file, the main one's first, once all have.
  std::optional<std::vector<std::string>> add(std::size_t part, std::int64_t step,
                                              std::string file) {
    auto& files = pending_[step];
    files.resize(parts_);
    files.at(part) = std::move(file);
    for (const auto& f : files) {
      if (f.empty()) return std::nullopt;
    }
    std::vector<std::string> complete = std::move(files);
    pending_.erase(step);
    return complete;
  }

 private:
  std::size_t parts_;
  std::map<std::int64_t, std::vector<std::string>> pending_;
};

}  // namespace pbms::coupler
