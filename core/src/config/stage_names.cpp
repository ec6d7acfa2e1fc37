#include "pbms/config/stage_names.hpp"

#include <algorithm>
#include <map>
#include <string>

#include <fmt/format.h>

namespace pbms::config {
namespace {

// The stage index of "stages[i]...", or -1 for a key outside the stages.
int stage_of(const std::string& key_path) {
  if (key_path.rfind("stages[", 0) != 0) return -1;
  return std::stoi(key_path.substr(7));
}

YAML::Mark mark_of(const Reference& r) {
  YAML::Mark m;
  m.line = r.line - 1;
  m.column = r.column - 1;
  return m;
}

// The key path of a declaration without its stage: "groups[1].name".
std::string within_stage(const std::string& key_path) {
  const auto dot = key_path.find("].");
  return dot == std::string::npos ? key_path : key_path.substr(dot + 2);
}

using Declarations = std::map<int, std::vector<const Reference*>>;

// Per stage, its declared names in order; a repeat is reported at the
// repeat, naming the first.
Declarations declarations(const std::vector<Reference>& refs, Validator& v) {
  Declarations by_stage;
  for (const auto& r : refs) {
    if (r.type != Reference::Target::kStageName) continue;
    const int stage = stage_of(r.key_path);
    auto& names = by_stage[stage];
    const auto first = std::find_if(names.begin(), names.end(),
                                    [&](const Reference* d) { return d->target == r.target; });
    if (first != names.end()) {
      v.error_at(mark_of(r), r.key_path,
                 fmt::format("the name '{}' is already given by {} (line {}): bodies and groups "
                             "share one set of names",
                             r.target, within_stage((*first)->key_path), (*first)->line));
      continue;
    }
    names.push_back(&r);
  }
  return by_stage;
}

std::string list_phrase(const std::vector<std::string>& lists) {
  return lists.size() == 1 ? lists[0] : fmt::format("{} or {}", lists[0], lists[1]);
}

void check_entry(const Reference& r, const Declarations& by_stage, Validator& v) {
  std::vector<std::string> known;
  const auto it = by_stage.find(stage_of(r.key_path));
  if (it != by_stage.end()) {
    for (const Reference* d : it->second) {
      if (std::find(r.kinds.begin(), r.kinds.end(), d->kinds[0]) != r.kinds.end()) {
        known.push_back(d->target);
      }
    }
  }
  if (std::find(known.begin(), known.end(), r.target) != known.end()) return;
  const std::string where =
      known.empty()
          ? fmt::format("this stage declares no {}", list_phrase(r.kinds))
          : fmt::format("this stage's {}: {}", list_phrase(r.kinds), fmt::join(known, ", "));
  v.error_at(mark_of(r), r.key_path,
             fmt::format("'{}' names no entry of {} ({}){}", r.target, list_phrase(r.kinds), where,
                         suggest(r.target, known)));
}

}  // namespace

void check_stage_names(const std::vector<Reference>& refs, Validator& v) {
  const Declarations by_stage = declarations(refs, v);
  for (const auto& r : refs) {
    if (r.type == Reference::Target::kStageEntry) check_entry(r, by_stage, v);
  }
}

}  // namespace pbms::config
