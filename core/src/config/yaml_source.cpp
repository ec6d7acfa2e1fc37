#include "pbms/config/yaml_source.hpp"

#include <algorithm>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>

namespace pbms::config {
namespace {

YAML::Mark mark_at(int line, int column) {
  YAML::Mark m;
  m.line = line;
  m.column = column;
  return m;
}

// Reports the first byte that cannot be part of a YAML text file (NUL, other
// control characters, malformed UTF-8) or the first line longer than
// kMaxYamlLineBytes. Returns false if one was found.
bool check_text(const std::string& text, Validator& v, const std::string& what) {
  int line = 0, col = 0;
  size_t line_start = 0;
  size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    size_t len = 1;
    bool bad = false;
    if ((c < 0x20 && c != '\n' && c != '\r' && c != '\t') || c == 0x7f) {
      bad = true;
    } else if (c >= 0x80) {
      if ((c & 0xE0) == 0xC0)
        len = 2;
      else if ((c & 0xF0) == 0xE0)
        len = 3;
      else if ((c & 0xF8) == 0xF0)
        len = 4;
      else
        bad = true;
      for (size_t k = 1; !bad && k < len; ++k) {
        bad = i + k >= text.size() || (static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80;
      }
    }
    if (bad) {
      v.error_at(mark_at(line, col), "",
                 fmt::format("not a text file: byte 0x{:02x} cannot appear in {}", c, what));
      return false;
    }
    if (c == '\n') {
      ++line;
      col = 0;
      line_start = i + 1;
    } else {
      ++col;
      if (i + 1 - line_start > kMaxYamlLineBytes) {
        size_t end = text.find('\n', i);
        if (end == std::string::npos) end = text.size();
        v.error_at(mark_at(line, 0), "",
                   fmt::format("line {} is {} bytes long; lines of {} are at most {} bytes",
                               line + 1, end - line_start, what, kMaxYamlLineBytes));
        return false;
      }
    }
    i += len;
  }
  return true;
}

// The alias written at `mark` ("*name"), for messages.
std::string alias_text(const std::string& text, const YAML::Mark& mark) {
  if (mark.pos < 0 || static_cast<size_t>(mark.pos) >= text.size()) return "an alias";
  size_t end = static_cast<size_t>(mark.pos) + 1;
  while (end < text.size() && end - static_cast<size_t>(mark.pos) < 64 &&
         std::string_view(" \t\r\n,]}").find(text[end]) == std::string_view::npos) {
    ++end;
  }
  return fmt::format("'{}'", text.substr(static_cast<size_t>(mark.pos), end - mark.pos));
}

// Walks the parser's events once before the document is built: yaml-cpp
// links an alias to the node it names, so an alias inside its own anchor
// builds a cycle that every later walk would follow forever, and nested
// aliases can multiply a small file into billions of values.
class AliasCheck : public YAML::EventHandler {
 public:
  AliasCheck(const std::string& text, Validator& v) : text_(text), v_(v) {}

  [[nodiscard]] bool failed() const { return failed_; }
  [[nodiscard]] int documents() const { return documents_; }
  [[nodiscard]] const YAML::Mark& last_document_mark() const { return document_mark_; }

  void OnDocumentStart(const YAML::Mark& mark) override {
    ++documents_;
    document_mark_ = mark;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t anchor) override { leaf(anchor, 1); }
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t anchor,
                const std::string& value) override {
    if (!stack_.empty() && stack_.back().map && stack_.back().key_next) {
      stack_.back().key = value.size() > 64 ? value.substr(0, 64) + "..." : value;
    }
    leaf(anchor, 1);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    if (failed_) return;
    if (open_.count(anchor)) {
      fail(mark, fmt::format("the alias {} stands inside the node its anchor names (line {}): "
                             "a recursive alias has no finite value",
                             alias_text(text_, mark), anchor_line_[anchor]));
      return;
    }
    const size_t n = size_[anchor];
    if (total_ + n > kMaxYamlValues) {
      fail(mark, fmt::format("the alias {} takes the document past {} values: aliases of "
                             "aliases multiply the values written",
                             alias_text(text_, mark), kMaxYamlValues));
      return;
    }
    leaf(0, n);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor, false);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, anchor, true);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Frame {
    bool map = false;
    bool key_next = true;  // map: the next node is a key
    size_t index = 0;      // sequence: index of the next element
    std::string key;       // map: the key of the value being read
    YAML::anchor_t anchor = 0;
    size_t values = 0;  // values inside, aliases expanded
  };

  // Key path of the node being read, as the validator writes it.
  [[nodiscard]] std::string path() const {
    std::string p;
    for (const auto& f : stack_) {
      if (f.map) {
        if (!f.key_next) p = join_path(p, f.key);
      } else {
        p += fmt::format("[{}]", f.index);
      }
    }
    return p;
  }

  void fail(const YAML::Mark& mark, const std::string& message) {
    v_.error_at(mark, path(), message);
    failed_ = true;
  }

  void open(const YAML::Mark& mark, YAML::anchor_t anchor, bool map) {
    if (anchor) {
      open_.insert(anchor);
      anchor_line_[anchor] = mark.line + 1;
    }
    Frame f;
    f.map = map;
    f.anchor = anchor;
    stack_.push_back(f);
  }

  void close() {
    const Frame f = stack_.back();
    stack_.pop_back();
    if (f.anchor) {
      open_.erase(f.anchor);
      size_[f.anchor] = f.values + 1;
    }
    advance(1, f.values);
  }

  void leaf(YAML::anchor_t anchor, size_t n) {
    if (anchor) size_[anchor] = n;
    total_ += n;
    advance(0, n);
  }

  // A node of `inner` values (plus `self` for a map or list itself) ended.
  void advance(size_t self, size_t inner) {
    total_ += self;
    if (stack_.empty()) return;
    auto& parent = stack_.back();
    parent.values += self + inner;
    if (parent.map) {
      parent.key_next = !parent.key_next;
    } else {
      ++parent.index;
    }
  }

  const std::string& text_;
  Validator& v_;
  std::vector<Frame> stack_;
  std::set<YAML::anchor_t> open_;
  std::map<YAML::anchor_t, size_t> size_;
  std::map<YAML::anchor_t, int> anchor_line_;
  size_t total_ = 0;
  bool failed_ = false;
  int documents_ = 0;
  YAML::Mark document_mark_;
};

}  // namespace

namespace {

// YAML merge keys (`<<: *defaults`, or a list of such maps): a map takes
// each merged map's keys it does not give itself, the first merged map
// first, and loses the `<<` key. yaml-cpp reads `<<` as a plain key. False
// (with the error) for a `<<` that holds anything but maps.
bool expand_merge_keys(YAML::Node node, Validator& v, int depth) {
  if (depth > 256) return true;  // the alias check bounds what the reader expands
  if (node.IsSequence()) {
    for (auto child : node) {
      if (!expand_merge_keys(child, v, depth + 1)) return false;
    }
    return true;
  }
  if (!node.IsMap()) return true;
  const YAML::Node& view = node;  // const lookups add no key
  const YAML::Node merged = view["<<"];
  if (merged) {
    std::vector<YAML::Node> sources;
    if (merged.IsMap()) sources.push_back(merged);
    for (std::size_t i = 0; merged.IsSequence() && i < merged.size(); ++i) {
      sources.push_back(merged[i]);
    }
    if (sources.empty() || !std::all_of(sources.begin(), sources.end(),
                                        [](const YAML::Node& m) { return m.IsMap(); })) {
      v.error(merged, "<<", "a merge key `<<` takes a map (`<<: *name`) or a list of maps");
      return false;
    }
    node.remove("<<");
    for (const YAML::Node& m : sources) {
      for (const auto& kv : m) {
        if (!view[kv.first.Scalar()]) node[kv.first.Scalar()] = kv.second;
      }
    }
  }
  for (auto kv : node) {
    if (!expand_merge_keys(kv.second, v, depth + 1)) return false;
  }
  return true;
}

}  // namespace

std::optional<YAML::Node> parse_yaml_source(const std::string& text, Validator& v,
                                            const std::string& what) {
  const YAML::Mark top = mark_at(0, 0);
  if (text.size() > kMaxYamlBytes) {
    v.error_at(top, "",
               fmt::format("the file is {} bytes; {} is at most {} bytes (1 MiB): is it the "
                           "right file?",
                           text.size(), what, kMaxYamlBytes));
    return std::nullopt;
  }
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    v.error_at(top, "", fmt::format("the file is empty: {} is a YAML map", what));
    return std::nullopt;
  }
  if (!check_text(text, v, what)) return std::nullopt;
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    AliasCheck check(text, v);
    while (!check.failed() && check.documents() < 2 && parser.HandleNextDocument(check)) {
    }
    if (check.failed()) return std::nullopt;
    if (check.documents() > 1) {
      v.error_at(check.last_document_mark(), "",
                 fmt::format("a second YAML document starts here: {} is one document (remove "
                             "the '---' or what follows it)",
                             what));
      return std::nullopt;
    }
    YAML::Node root = YAML::Load(text);
    if (root.IsNull() || !root.IsDefined()) {
      v.error_at(
          root.IsDefined() && !root.Mark().is_null() ? root.Mark() : top, "",
          fmt::format("the file holds no YAML value (only comments?): {} is a YAML map", what));
      return std::nullopt;
    }
    if (!expand_merge_keys(root, v, 0)) return std::nullopt;
    return root;
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp stops at a parser depth of 2000 (its message says only "bad file").
    v.error_at(e.mark, "",
               fmt::format("lists and maps are nested too deep for the YAML reader (parser depth "
                           "{}): {} is a shallow tree",
                           e.depth(), what));
    return std::nullopt;
  } catch (const YAML::ParserException& e) {
    v.error_at(e.mark, "", fmt::format("YAML syntax error: {}", e.msg));
    return std::nullopt;
  }
}

std::optional<YAML::Node> load_yaml_source(const std::string& path, Validator& v,
                                           const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    v.error_at(mark_at(0, 0), "", fmt::format("cannot open {}: {}", what, std::strerror(errno)));
    return std::nullopt;
  }
  // Never reads more than one byte past the limit, whatever the file's size.
  std::string text(kMaxYamlBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<size_t>(in.gcount()));
  if (text.size() > kMaxYamlBytes) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    v.error_at(mark_at(0, 0), "",
               fmt::format("the file is {} bytes; {} is at most {} bytes (1 MiB): is it the "
                           "right file?",
                           ec ? fmt::format("over {}", kMaxYamlBytes) : std::to_string(size), what,
                           kMaxYamlBytes));
    return std::nullopt;
  }
  return parse_yaml_source(text, v, what);
}

}  // namespace pbms::config
