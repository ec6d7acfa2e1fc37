#include "pbms/geometry/region_spec.hpp"

#include <set>
#include <utility>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/geometry/composite_regions.hpp"
#include "pbms/geometry/primitive_regions.hpp"

namespace pbms::geometry {

namespace {

// Reads the parameters of one primitive spec and remembers which it read, so
// that finish() can reject every other one by name.
class ParamReader {
 public:
  // `expected` lists the style's parameters for error messages.
  ParamReader(const RegionSpec& spec, std::string expected)
      : spec_(spec), expected_(std::move(expected)) {
    if (!spec.children.empty()) {
      throw Error(fmt::format("takes no child regions, got {}", spec.children.size()));
    }
  }

  std::vector<double> numbers(const std::string& key, std::size_t count) {
    used_.insert(key);
    const auto it = spec_.params.find(key);
    if (it == spec_.params.end()) {
      if (spec_.words.count(key)) {
        throw Error(fmt::format("parameter '{}' must be numbers, got the word '{}'", key,
                                spec_.words.at(key)));
      }
      throw Error(fmt::format("missing parameter '{}'; expected {}", key, expected_));
    }
    if (it->second.size() != count) {
      throw Error(fmt::format("parameter '{}' needs {} number{}, got {}", key, count,
                              count == 1 ? "" : "s", it->second.size()));
    }
    return it->second;
  }

  double scalar(const std::string& key) { return numbers(key, 1)[0]; }

  Vec3 vec3(const std::string& key) {
    const auto v = numbers(key, 3);
    return {v[0], v[1], v[2]};
  }

  std::array<double, 2> pair(const std::string& key) {
    const auto v = numbers(key, 2);
    return {v[0], v[1]};
  }

  const std::string& word(const std::string& key) {
    used_.insert(key);
    const auto it = spec_.words.find(key);
    if (it == spec_.words.end()) {
      if (spec_.params.count(key)) throw Error(fmt::format("parameter '{}' must be a word", key));
      throw Error(fmt::format("missing parameter '{}'; expected {}", key, expected_));
    }
    return it->second;
  }

  void finish() const {
    for (const auto& [key, v] : spec_.params) reject_unused(key);
    for (const auto& [key, w] : spec_.words) reject_unused(key);
  }

 private:
  void reject_unused(const std::string& key) const {
    if (!used_.count(key)) {
      throw Error(fmt::format("unknown parameter '{}'; expected {}", key, expected_));
    }
  }

  const RegionSpec& spec_;
  std::string expected_;
  std::set<std::string> used_;
};

Axis axis_from_word(const std::string& w) {
  if (w == "x") return Axis::kX;
  if (w == "y") return Axis::kY;
  if (w == "z") return Axis::kZ;
  throw Error(fmt::format("axis must be x, y or z, got '{}'", w));
}

std::unique_ptr<Region> make_block(const RegionSpec& spec) {
  ParamReader p(spec, "lo[3], hi[3]");
  const Vec3 lo = p.vec3("lo");
  const Vec3 hi = p.vec3("hi");
  p.finish();
  return std::make_unique<BlockRegion>(lo, hi);
}

std::unique_ptr<Region> make_sphere(const RegionSpec& spec) {
  ParamReader p(spec, "centre[3], radius");
  const Vec3 centre = p.vec3("centre");
  const double radius = p.scalar("radius");
  p.finish();
  return std::make_unique<SphereRegion>(centre, radius);
}

std::unique_ptr<Region> make_cylinder(const RegionSpec& spec) {
  ParamReader p(spec, "axis (x, y or z), centre[2], radius, lo, hi");
  const Axis axis = axis_from_word(p.word("axis"));
  const auto centre = p.pair("centre");
  const double radius = p.scalar("radius");
  const double lo = p.scalar("lo");
  const double hi = p.scalar("hi");
  p.finish();
  return std::make_unique<CylinderRegion>(axis, centre, radius, lo, hi);
}

// The children of a boolean style, built recursively; an error names the
// child by its position, as a config path would.
std::vector<RegionPtr> children_of(const RegionSpec& spec) {
  if (!spec.params.empty()) {
    throw Error(fmt::format("takes no parameters, got '{}'", spec.params.begin()->first));
  }
  if (!spec.words.empty()) {
    throw Error(fmt::format("takes no parameters, got '{}'", spec.words.begin()->first));
  }
  if (spec.children.size() < 2) {
    throw Error(fmt::format("needs at least two child regions, got {}", spec.children.size()));
  }
  std::vector<RegionPtr> parts;
  for (std::size_t i = 0; i < spec.children.size(); ++i) {
    try {
      parts.push_back(RegionRegistry::create(spec.children[i]));
    } catch (const Error& e) {
      throw Error(fmt::format("children[{}]: {}", i, e.what()));
    }
  }
  return parts;
}

using Table = std::map<std::string, RegionRegistry::Factory, std::less<>>;

// The built-in styles; a new shape adds its line here.
Table& table() {
  static Table t{
      {"block", make_block},
      {"sphere", make_sphere},
      {"cylinder", make_cylinder},
      {"union", [](const RegionSpec& s) { return std::make_unique<UnionRegion>(children_of(s)); }},
      {"intersection",
       [](const RegionSpec& s) { return std::make_unique<IntersectionRegion>(children_of(s)); }},
      {"difference",
       [](const RegionSpec& s) -> std::unique_ptr<Region> {
         auto parts = children_of(s);
         RegionPtr base = std::move(parts.front());
         parts.erase(parts.begin());
         RegionPtr removed = parts.size() == 1
                                 ? std::move(parts.front())
                                 : std::make_shared<const UnionRegion>(std::move(parts));
         return std::make_unique<DifferenceRegion>(std::move(base), std::move(removed));
       }},
  };
  return t;
}

std::string joined_names() {
  std::string s;
  for (const auto& [name, factory] : table()) s += (s.empty() ? "" : ", ") + name;
  return s;
}

}  // namespace

std::unique_ptr<Region> RegionRegistry::create(const RegionSpec& spec) {
  const auto it = table().find(spec.style);
  if (it == table().end()) {
    throw Error(
        fmt::format("unknown region style '{}'; available: {}", spec.style, joined_names()));
  }
  try {
    auto region = it->second(spec);
    if (!region) throw Error("the style's factory built no region");
    return region;
  } catch (const Error& e) {
    throw Error(fmt::format("region '{}': {}", spec.style, e.what()));
  }
}

std::vector<std::string> RegionRegistry::names() {
  std::vector<std::string> out;
  for (const auto& [name, factory] : table()) out.push_back(name);
  return out;
}

bool RegionRegistry::contains(std::string_view style) {
  return table().find(style) != table().end();
}

void RegionRegistry::add(std::string style, Factory factory) {
  if (style.empty() || !factory) throw Error("a region style needs a name and a factory");
  if (contains(style)) throw Error(fmt::format("region style '{}' is already registered", style));
  table().emplace(std::move(style), std::move(factory));
}

}  // namespace pbms::geometry
