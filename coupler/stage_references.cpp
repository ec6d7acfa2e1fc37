#include "stage_references.hpp"

#include <cmath>

#include <fmt/format.h>

#include "pbms/units.hpp"

namespace pbms::coupler {
// A table output as a map of its columns, each with its unit.
namespace {

YAML::Node table_node(const StageResults& results, const std::string& table) {
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& c : results.columns) {
    if (c.table != table) continue;
    out[c.name]["unit"] = c.unit;
    out[c.name]["values"] = c.data;
  }
  return out;
}

}  // namespace

YAML::Node resolve_references(const YAML::Node& node,
                              const std::map<std::string, StageResults>& done,
                              const std::string& path) {
  if (node.IsMap() && node.size() == 1 && node["from"] && node["from"].IsScalar()) {
    const std::string target = node["from"].Scalar();
    const auto dot = target.find('.');
    const std::string stage = target.substr(0, dot), key = target.substr(dot + 1);
    const auto it = done.find(stage);
    if (it != done.end()) {
      for (const auto& s : it->second.scalars) {
        if (s.key != key) continue;
        if (!std::isfinite(s.value)) {
          throw NonFiniteReference(
              fmt::format("{}: {{from: {}}} is {} {}: stage '{}' did not measure it (its "
                          "summary and report say why), and this stage would run on it",
                          path, target, s.value, s.unit, stage));
        }
        return YAML::Node(units::to_metal(s.value, s.unit));
      }
      YAML::Node table = table_node(it->second, key);
      if (table.size() > 0) return table;
      // A map output (a fitted potential) travels as YAML text.
      const auto attr = it->second.attributes.find(key);
      if (attr != it->second.attributes.end()) {
        YAML::Node map = YAML::Load(attr->second);
        if (map.IsMap()) return map;
      }
    }
    throw Error(fmt::format("stage '{}' did not produce '{}'", stage, key));
  }
  if (node.IsMap()) {
    YAML::Node out(YAML::NodeType::Map);
    for (const auto& kv : node) {
      out[kv.first] = resolve_references(kv.second, done, path + "." + kv.first.Scalar());
    }
    return out;
  }
  if (node.IsSequence()) {
    YAML::Node out(YAML::NodeType::Sequence);
    for (std::size_t i = 0; i < node.size(); ++i) {
      out.push_back(resolve_references(node[i], done, fmt::format("{}[{}]", path, i)));
    }
    return out;
  }
  return node;
}

YAML::Node resolve_materials(const YAML::Node& materials,
                             const std::map<std::string, StageResults>& done) {
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& kv : materials) {
    try {
      out[kv.first] = resolve_references(kv.second, done, "materials." + kv.first.Scalar());
    } catch (const NonFiniteReference&) {
      throw;
    } catch (const Error&) {
      // Refers to a stage that has not run yet: not this stage's material.
    }
  }
  return out;
}

}  // namespace pbms::coupler
