#include "pbms/config/validator.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <fmt/format.h>

namespace pbms::config {
namespace {

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// [A-Za-z_][A-Za-z0-9_.-]*, without std::regex: libstdc++'s regex matcher
// recurses once per character, and a name of a few megabytes overflows the
// stack (a segmentation fault instead of an error).
bool is_name(const std::string& s) {
  if (s.empty()) return false;
  const auto c0 = static_cast<unsigned char>(s[0]);
  if (!(std::isalpha(c0) || c0 == '_')) return false;
  return std::all_of(s.begin() + 1, s.end(), [](char ch) {
    const auto c = static_cast<unsigned char>(ch);
    return std::isalnum(c) || c == '_' || c == '.' || c == '-';
  });
}

// The first part of `p` (itself included) that exists but is not a
// directory, so that nothing below it can exist (ENOTDIR); empty if none.
std::filesystem::path blocking_file(const std::filesystem::path& p) {
  std::filesystem::path prefix;
  for (const auto& part : p) {
    prefix /= part;
    struct stat st {};
    if (::stat(prefix.c_str(), &st) != 0) return {};
    if (!S_ISDIR(st.st_mode)) return prefix;
  }
  return {};
}

std::string shown(const YAML::Node& n) {
  if (n.IsScalar()) {
    const auto& s = n.Scalar();
    // Long or multi-line values (an unclosed quote swallows the file) are cut.
    const auto cut = std::min<size_t>(s.find('\n'), 40);
    return cut >= s.size() ? fmt::format("'{}'", s) : fmt::format("'{}...'", s.substr(0, cut));
  }
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  return "nothing";
}

bool is_reference(const YAML::Node& n) {
  return n.IsMap() && n.size() == 1 && n["from"] && n["from"].IsScalar();
}

}  // namespace

std::string file_problem(const std::filesystem::path& file) {
  const auto f = std::filesystem::absolute(file).lexically_normal();
  const auto blocked = blocking_file(f.parent_path());
  if (!blocked.empty()) {
    return fmt::format("cannot exist: '{}' is a file, not a directory", blocked.string());
  }
  struct stat st {};
  if (::stat(f.c_str(), &st) != 0) {
    return errno == ENOENT ? std::string("does not exist")
                           : fmt::format("cannot be reached: {}", std::strerror(errno));
  }
  if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
  if (!S_ISREG(st.st_mode)) return "is not a regular file";
  if (!std::ifstream(f).good()) return fmt::format("cannot be read: {}", std::strerror(errno));
  return {};
}

std::string directory_problem(const std::filesystem::path& dir) {
  const auto d = std::filesystem::absolute(dir).lexically_normal();
  const auto blocked = blocking_file(d);
  if (!blocked.empty()) {
    return blocked == d ? fmt::format("'{}' exists and is not a directory", d.string())
                        : fmt::format("'{}' is a file, not a directory", blocked.string());
  }
  // The deepest part that exists must let us create (or write) inside it.
  auto existing = d;
  std::error_code ec;
  while (!std::filesystem::exists(existing, ec) && existing.has_parent_path() &&
         existing != existing.parent_path()) {
    existing = existing.parent_path();
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0) {
    return fmt::format("'{}' cannot be written: {}", existing.string(), std::strerror(errno));
  }
  return {};
}

std::string clipped(const std::string& s, size_t n) {
  return s.size() <= n ? s : s.substr(0, n) + "...";
}

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string suggest(const std::string& key, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_d = 3;
  for (const auto& c : candidates) {
    const size_t d = edit_distance(key, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", best);
}

void Validator::error_at(const YAML::Mark& mark, const std::string& path,
                         const std::string& message) {
  ConfigError e;
  e.file = file_;
  if (!mark.is_null()) {
    e.line = mark.line + 1;
    e.column = mark.column + 1;
  }
  e.key_path = path;
  e.message = message;
  errors_.push_back(std::move(e));
}

void Validator::error(const YAML::Node& at, const std::string& path, const std::string& message) {
  error_at(at.IsDefined() ? at.Mark() : YAML::Mark::null_mark(), path, message);
}

void Validator::warn(const YAML::Node& at, const std::string& path, const std::string& message) {
  error(at, path, message);
  ConfigError w = std::move(errors_.back());
  errors_.pop_back();
  w.warning = true;
  warnings_.push_back(std::move(w));
}

bool Validator::check_range(const Param& p, double v, const YAML::Node& node,
                            const std::string& path) {
  const auto unit = units::canonical_symbol(p.dimension);
  const std::string u = p.dimension == units::Dimension::kNone ? "" : fmt::format(" {}", unit);
  if (p.min && (p.min_exclusive ? !(v > *p.min) : !(v >= *p.min))) {
    error(node, path,
          fmt::format("value {}{} is out of range: must be {} {}{}", v, u,
                      p.min_exclusive ? ">" : ">=", *p.min, u));
    return false;
  }
  if (p.max && (p.max_exclusive ? !(v < *p.max) : !(v <= *p.max))) {
    error(node, path,
          fmt::format("value {}{} is out of range: must be {} {}{}", v, u,
                      p.max_exclusive ? "<" : "<=", *p.max, u));
    return false;
  }
  return true;
}

YAML::Node Validator::check_scalar(const Param& p, const YAML::Node& node,
                                   const std::string& path) {
  if (!node.IsScalar()) {
    error(node, path, fmt::format("expected {}, got {}", p.type_text(), shown(node)));
    return {};
  }
  const std::string& s = node.Scalar();
  if (s.find('\n') != std::string::npos && p.kind != ParamKind::kString) {
    // yaml-cpp lets an unclosed quote run to the end of the file.
    error(node, path,
          fmt::format("the value {} runs over several lines: is a quote left open?", shown(node)));
    return {};
  }
  switch (p.kind) {
    case ParamKind::kInteger:
      return check_integer(p, node, path);
    case ParamKind::kReal:
      return check_real(p, node, path);
    case ParamKind::kBoolean: {
      try {
        return YAML::Node(node.as<bool>());
      } catch (const YAML::Exception&) {
        error(node, path, fmt::format("expected true or false, got '{}'", clipped(s)));
        return {};
      }
    }
    case ParamKind::kString:
      return YAML::Node(s);
    case ParamKind::kName: {
      if (!is_name(s)) {
        error(node, path,
              fmt::format("'{}' is not a valid name: use letters, digits, '_', '-' and '.', "
                          "starting with a letter or '_'",
                          clipped(s)));
        return {};
      }
      return YAML::Node(s);
    }
    case ParamKind::kFile:
      return check_file(node, path);
    case ParamKind::kPath:
      if (s.empty()) {
        error(node, path, "path is empty");
        return {};
      }
      return YAML::Node(s);
    case ParamKind::kChoice:
      if (std::find(p.choices.begin(), p.choices.end(), s) == p.choices.end()) {
        error(node, path,
              fmt::format("'{}' is not one of: {}{}", clipped(s), fmt::join(p.choices, ", "),
                          suggest(s, p.choices)));
        return {};
      }
      return YAML::Node(s);
    default:
      break;
  }
  return {};
}

YAML::Node Validator::check_integer(const Param& p, const YAML::Node& node,
                                    const std::string& path) {
  long long v = 0;
  try {
    v = node.as<long long>();
  } catch (const YAML::Exception&) {
    error(node, path, fmt::format("expected an integer, got '{}'", clipped(node.Scalar())));
    return {};
  }
  // Unless a key says otherwise, integers are counts that drivers hold
  // in an int: a larger value would be cut, not refused, at run time.
  if (!p.max && v > INT_MAX) {
    error(node, path, fmt::format("value {} is too large: at most {}", v, INT_MAX));
    return {};
  }
  if (!p.min && v < INT_MIN) {
    error(node, path, fmt::format("value {} is too small: at least {}", v, INT_MIN));
    return {};
  }
  if (!check_range(p, static_cast<double>(v), node, path)) return {};
  return YAML::Node(v);
}

YAML::Node Validator::check_real(const Param& p, const YAML::Node& node, const std::string& path) {
  const std::string& s = node.Scalar();
  if (p.allow_auto && s == "auto") return YAML::Node("auto");
  double v = 0.0;
  try {
    v = units::parse_quantity(s, p.dimension);
  } catch (const Error& e) {
    error(node, path, fmt::format("expected {}: {}", p.type_text(), e.what()));
    return {};
  }
  if (!check_range(p, v, node, path)) return {};
  return YAML::Node(v);
}

YAML::Node Validator::check_file(const YAML::Node& node, const std::string& path) {
  // Relative to the config file, so that a config means the same from any folder.
  std::filesystem::path f(node.Scalar());
  if (f.is_relative()) f = std::filesystem::path(file_).parent_path() / f;
  if (const std::string problem = file_problem(f); !problem.empty()) {
    error(node, path, fmt::format("file '{}' {}", clipped(f.string(), 300), problem));
    return {};
  }
  return YAML::Node(std::filesystem::absolute(f).lexically_normal().string());
}

void Validator::check_unique_keys(const YAML::Node& node, const std::string& path) {
  // yaml-cpp keeps both entries of a repeated key and looks up the first:
  // the second would be ignored without a word.
  std::map<std::string, int> first_line;
  for (const auto& kv : node) {
    if (!kv.first.IsScalar()) continue;
    const auto key = kv.first.Scalar();
    const int line = kv.first.Mark().line + 1;
    const auto [it, fresh] = first_line.emplace(key, line);
    if (!fresh) {
      error(kv.first, join_path(path, clipped(key)),
            fmt::format("the key '{}' is given twice in this map (first on line {}); keep one",
                        clipped(key), it->second));
    }
  }
}

YAML::Node Validator::check_fields(const std::vector<const Param*>& fields, const YAML::Node& node,
                                   const std::string& path) {
  YAML::Node out(YAML::NodeType::Map);
  std::vector<std::string> names;
  for (const auto* f : fields) names.push_back(f->name);
  check_unique_keys(node, path);
  for (const auto& kv : node) {
    const auto key = kv.first.Scalar();
    if (std::find(names.begin(), names.end(), key) == names.end()) {
      error(kv.first, join_path(path, clipped(key)),
            fmt::format("unknown key '{}'{}", clipped(key), suggest(key, names)));
    }
  }
  for (const auto* f : fields) {
    const YAML::Node child = node[f->name];
    const std::string child_path = join_path(path, f->name);
    if (!child.IsDefined()) {
      if (f->required) {
        error(node, child_path, fmt::format("required key '{}' is missing", f->name));
      } else if (f->default_value) {
        out[f->name] = YAML::Clone(*f->default_value);
      }
      continue;
    }
    if (child.IsNull()) {
      error(child, child_path,
            fmt::format("'{}' has no value: expected {}", f->name, f->type_text()));
      continue;
    }
    YAML::Node resolved = check(*f, child, child_path);
    if (resolved.IsDefined() && !resolved.IsNull()) out[f->name] = resolved;
  }
  check_only_with(fields, node, out, path);
  check_exclusions(fields, node, path);
  return out;
}

void Validator::check_exclusions(const std::vector<const Param*>& fields, const YAML::Node& node,
                                 const std::string& path) {
  const auto given = [&node](const std::string& key) {
    const YAML::Node n = node[key];
    return n.IsDefined() && !n.IsNull() && !(n.IsSequence() && n.size() == 0);
  };
  for (const auto* f : fields) {
    if (f->excludes.empty() || !given(f->name) || !given(f->excludes)) continue;
    error(node[f->name], join_path(path, f->name),
          fmt::format("'{}' and '{}' are given together; a stage takes one or the other", f->name,
                      f->excludes));
  }
}

void Validator::check_only_with(const std::vector<const Param*>& fields, const YAML::Node& node,
                                const YAML::Node& resolved, const std::string& path) {
  for (const auto* f : fields) {
    const auto& [key, value] = f->only_with;
    if (key.empty() || !node[f->name].IsDefined()) continue;
    const YAML::Node other = resolved[key];
    const std::string actual = other.IsDefined() && other.IsScalar() ? other.Scalar() : "";
    if (actual == value) continue;
    error(node[f->name], join_path(path, f->name),
          fmt::format("'{}' applies only with {}: {}{}", f->name, key, value,
                      actual.empty() ? "" : fmt::format(" (here {} is '{}')", key, actual)));
  }
  for (const auto* f : fields) {
    const auto& [key, value] = f->required_with;
    if (key.empty() || node[f->name].IsDefined()) continue;
    const YAML::Node other = resolved[key];
    if (!other.IsDefined() || !other.IsScalar() || other.Scalar() != value) continue;
    error(node, join_path(path, f->name),
          fmt::format("required key '{}' is missing: {}: {} needs it", f->name, key, value));
  }
}

YAML::Node Validator::check(const Param& p, const YAML::Node& node, const std::string& path) {
  if (p.allow_reference && is_reference(node)) return record_stage_output_reference(p, node, path);
  switch (p.kind) {
    case ParamKind::kTable:
      error(node, path,
            fmt::format("expected a table of an earlier stage, written {{from: <stage>.<table>}}; "
                        "got {}",
                        shown(node)));
      return {};
    case ParamKind::kMap:
      return check_map(p, node, path);
    case ParamKind::kMapOf:
      return check_map_of(p, node, path);
    case ParamKind::kListOf:
    case ParamKind::kRealList:
    case ParamKind::kIntList:
      return check_list(p, node, path);
    default:
      return check_leaf(p, node, path);
  }
}

YAML::Node Validator::record_stage_output_reference(const Param& p, const YAML::Node& node,
                                                    const std::string& path) {
  Reference r;
  r.key_path = path;
  r.target = node["from"].Scalar();
  r.line = node["from"].Mark().line + 1;
  r.column = node["from"].Mark().column + 1;
  r.wants = p.kind == ParamKind::kTable ? OutputSpec::Shape::kTable
            : p.kind == ParamKind::kMap ? OutputSpec::Shape::kMap
                                        : OutputSpec::Shape::kScalar;
  references_.push_back(r);
  return YAML::Clone(node);
}

YAML::Node Validator::check_map(const Param& p, const YAML::Node& node, const std::string& path) {
  if (!node.IsMap()) {
    error(node, path, fmt::format("expected a map, got {}", shown(node)));
    return {};
  }
  std::string variant;
  if (!p.discriminator.empty()) {
    const YAML::Node d = node[p.discriminator];
    if (d.IsDefined() && d.IsScalar()) variant = d.Scalar();
  }
  std::vector<const Param*> fields = p.fields_for(variant);
  if (p.one_key && node.size() != 1) {
    std::vector<std::string> names;
    for (const auto* f : fields) names.push_back(f->name);
    error(node, path,
          fmt::format("takes exactly one of {}; {} given", fmt::join(names, ", "), node.size()));
    return {};
  }
  if (!p.discriminator.empty() && !p.variants.count(variant)) {
    // Only validate the common keys; the unknown variant is reported by the
    // discriminator's choice check. Extra keys would only add noise.
    YAML::Node partial(YAML::NodeType::Map);
    for (const auto* f : fields) {
      if (node[f->name]) partial[f->name] = node[f->name];
    }
    return check_fields(fields, node[p.discriminator].IsDefined() ? partial : node, path);
  }
  YAML::Node out = check_fields(fields, node, path);
  if (!p.lower_upper.first.empty() && out.IsMap()) check_bounds(p, node, out, path);
  return out;
}

// Param::bounds: each lower entry below its upper one, reported at the
// upper key with the axis that is empty.
void Validator::check_bounds(const Param& p, const YAML::Node& node, const YAML::Node& out,
                             const std::string& path) {
  const auto& [lo_key, hi_key] = p.lower_upper;
  const YAML::Node lo = out[lo_key], hi = out[hi_key];
  if (!lo.IsDefined() || !hi.IsDefined() || lo.Type() != hi.Type()) return;
  std::vector<double> l, h;
  try {
    if (lo.IsSequence() && lo.size() == hi.size()) {
      l = lo.as<std::vector<double>>();
      h = hi.as<std::vector<double>>();
    } else if (lo.IsScalar()) {
      l = {lo.as<double>()};
      h = {hi.as<double>()};
    }
  } catch (const YAML::Exception&) {
    return;  // not numbers: reported by the keys' own checks
  }
  for (size_t a = 0; a < l.size(); ++a) {
    if (l[a] < h[a]) continue;
    const std::string axis = l.size() == 3 ? fmt::format(" along {}", "xyz"[a]) : "";
    error(node[hi_key], join_path(path, hi_key),
          fmt::format("{} {:g} is not above {} {:g}{}: the {} holds nothing", hi_key, h[a], lo_key,
                      l[a], axis, p.name));
    return;
  }
}

YAML::Node Validator::check_map_of(const Param& p, const YAML::Node& node,
                                   const std::string& path) {
  if (!node.IsMap()) {
    error(node, path, fmt::format("expected a map of named entries, got {}", shown(node)));
    return {};
  }
  YAML::Node out(YAML::NodeType::Map);
  check_unique_keys(node, path);
  for (const auto& kv : node) {
    const auto key = kv.first.Scalar();
    const auto child_path = join_path(path, key);
    if (!is_name(key)) {
      error(kv.first, join_path(path, clipped(key)),
            fmt::format("'{}' is not a valid name", clipped(key)));
      continue;
    }
    out[key] = check(p.fields[0], kv.second, child_path);
  }
  return out;
}

YAML::Node Validator::check_list(const Param& p, const YAML::Node& node, const std::string& path) {
  if (!node.IsSequence()) {
    error(node, path, fmt::format("expected a list, got {}", shown(node)));
    return {};
  }
  if (p.min_length && node.size() < *p.min_length) {
    error(node, path, fmt::format("needs at least {} entries, has {}", *p.min_length, node.size()));
  }
  if (p.max_length && node.size() > *p.max_length) {
    error(node, path, fmt::format("takes at most {} entries, has {}", *p.max_length, node.size()));
  }
  if (!p.lengths.empty() &&
      std::find(p.lengths.begin(), p.lengths.end(), node.size()) == p.lengths.end()) {
    error(node, path,
          fmt::format("takes {} entries, has {}", fmt::join(p.lengths, " or "), node.size()));
  }
  Param element;
  if (p.kind == ParamKind::kListOf) {
    element = p.fields[0];
  } else {
    element = p;
    element.kind = p.kind == ParamKind::kRealList ? ParamKind::kReal : ParamKind::kInteger;
  }
  YAML::Node out(YAML::NodeType::Sequence);
  for (size_t i = 0; i < node.size(); ++i) {
    const std::string element_path = fmt::format("{}[{}]", path, i);
    out.push_back(check(element, node[i], element_path));
    if (p.declares_names) declare_name(p.name, node[i], element_path);
  }
  return out;
}

void Validator::declare_name(const std::string& list, const YAML::Node& entry,
                             const std::string& path) {
  const YAML::Node name = entry.IsMap() ? entry["name"] : YAML::Node();
  if (!name.IsDefined() || !name.IsScalar()) return;
  references_.push_back(
      reference(Reference::Target::kStageName, name, join_path(path, "name"), {list}));
}

Reference Validator::reference(Reference::Target type, const YAML::Node& node,
                               const std::string& path, std::vector<std::string> kinds) {
  Reference r;
  r.type = type;
  r.key_path = path;
  r.target = node.Scalar();
  r.kinds = std::move(kinds);
  r.line = node.Mark().line + 1;
  r.column = node.Mark().column + 1;
  return r;
}

YAML::Node Validator::check_leaf(const Param& p, const YAML::Node& node, const std::string& path) {
  YAML::Node out = check_scalar(p, node, path);
  if (!out.IsDefined() || out.IsNull()) return out;
  if (p.names_material) references_.push_back(reference(Reference::Target::kMaterial, node, path));
  if (!p.stage_kinds.empty()) {
    references_.push_back(reference(Reference::Target::kStage, node, path, p.stage_kinds));
  }
  if (!p.entry_lists.empty()) {
    references_.push_back(reference(Reference::Target::kStageEntry, node, path, p.entry_lists));
  }
  return out;
}

}  // namespace pbms::config
