#include "pbms/config/stage_kind_spec.hpp"

namespace pbms::config {
namespace {

OutputSpec::Shape shape_from_name(const std::string& name) {
  if (name == "table") return OutputSpec::Shape::kTable;
  if (name == "map") return OutputSpec::Shape::kMap;
  return OutputSpec::Shape::kScalar;
}

}  // namespace

const char* shape_name(OutputSpec::Shape shape) {
  switch (shape) {
    case OutputSpec::Shape::kScalar:
      return "scalar";
    case OutputSpec::Shape::kTable:
      return "table";
    case OutputSpec::Shape::kMap:
      return "map";
  }
  return "scalar";
}

const OutputSpec* StageKindSpec::output(std::string_view name) const {
  for (const auto& o : outputs) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

const StageKindSpec* DriverDescription::stage_kind(std::string_view kind) const {
  for (const auto& s : stage_kinds) {
    if (s.kind == kind) return &s;
  }
  return nullptr;
}

YAML::Node to_yaml(const StageKindSpec& s) {
  YAML::Node n;
  n["kind"] = s.kind;
  n["program"] = s.program;
  n["doc"] = s.doc;
  n["params"] = YAML::Node(YAML::NodeType::Sequence);
  for (const auto& p : s.params) n["params"].push_back(to_yaml(p));
  n["outputs"] = YAML::Node(YAML::NodeType::Sequence);
  for (const auto& o : s.outputs) {
    YAML::Node on;
    on["name"] = o.name;
    on["shape"] = shape_name(o.shape);
    on["unit"] = o.unit;
    on["doc"] = o.doc;
    n["outputs"].push_back(on);
  }
  n["material_kinds"] = s.material_kinds;
  if (s.cacheable) n["cacheable"] = true;
  if (s.checkpoints) n["checkpoints"] = true;
  if (!s.uses.empty()) n["uses"] = s.uses;
  for (const auto& p : s.partners) {
    YAML::Node pn;
    pn["program"] = p.program;
    pn["kind"] = p.kind;
    n["partners"].push_back(pn);
  }
  if (s.internal) n["internal"] = true;
  return n;
}

StageKindSpec stage_kind_from_yaml(const YAML::Node& n) {
  StageKindSpec s;
  s.kind = n["kind"].as<std::string>();
  s.program = n["program"].as<std::string>();
  s.doc = n["doc"].as<std::string>("");
  for (const auto& p : n["params"]) s.params.push_back(param_from_yaml(p));
  for (const auto& on : n["outputs"]) {
    OutputSpec o;
    o.name = on["name"].as<std::string>();
    o.shape = shape_from_name(on["shape"].as<std::string>());
    o.unit = on["unit"].as<std::string>("");
    o.doc = on["doc"].as<std::string>("");
    s.outputs.push_back(o);
  }
  if (n["material_kinds"]) s.material_kinds = n["material_kinds"].as<std::vector<std::string>>();
  s.cacheable = n["cacheable"] && n["cacheable"].as<bool>();
  s.checkpoints = n["checkpoints"] && n["checkpoints"].as<bool>();
  if (n["uses"]) s.uses = n["uses"].as<std::vector<std::string>>();
  for (const auto& pn : n["partners"]) {
    s.partners.push_back({pn["program"].as<std::string>(), pn["kind"].as<std::string>()});
  }
  s.internal = n["internal"] && n["internal"].as<bool>();
  return s;
}

const MaterialKindSpec* find_material_kind(const std::vector<DriverDescription>& drivers,
                                           std::string_view kind) {
  for (const auto& d : drivers) {
    for (const auto& m : d.material_kinds) {
      if (m.kind == kind) return &m;
    }
  }
  return nullptr;
}

const Param* material_field(const std::vector<DriverDescription>& drivers, std::string_view kind,
                            std::string_view name) {
  const MaterialKindSpec* m = find_material_kind(drivers, kind);
  if (!m) return nullptr;
  for (const auto& p : m->params) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

YAML::Node to_yaml(const DriverDescription& d) {
  YAML::Node n;
  n["program"] = d.program;
  n["short_name"] = d.short_name;
  n["protocol_version"] = d.protocol_version;
  for (const auto& [k, v] : d.software) n["software"][k] = v;
  n["stage_kinds"] = YAML::Node(YAML::NodeType::Sequence);
  for (const auto& s : d.stage_kinds) n["stage_kinds"].push_back(to_yaml(s));
  for (const auto& m : d.material_kinds) {
    YAML::Node mn;
    mn["kind"] = m.kind;
    mn["doc"] = m.doc;
    mn["params"] = YAML::Node(YAML::NodeType::Sequence);
    for (const auto& p : m.params) mn["params"].push_back(to_yaml(p));
    n["material_kinds"].push_back(mn);
  }
  return n;
}

DriverDescription driver_from_yaml(const YAML::Node& n) {
  DriverDescription d;
  d.program = n["program"].as<std::string>();
  d.short_name = n["short_name"].as<std::string>();
  d.protocol_version = n["protocol_version"].as<int>();
  for (const auto& kv : n["software"]) {
    d.software.emplace_back(kv.first.as<std::string>(), kv.second.as<std::string>());
  }
  for (const auto& s : n["stage_kinds"]) d.stage_kinds.push_back(stage_kind_from_yaml(s));
  for (const auto& mn : n["material_kinds"]) {
    MaterialKindSpec m{mn["kind"].as<std::string>(), mn["doc"].as<std::string>(""), {}};
    for (const auto& p : mn["params"]) m.params.push_back(param_from_yaml(p));
    d.material_kinds.push_back(std::move(m));
  }
  return d;
}

YAML::Node stage_named(const YAML::Node& workflow, const std::string& name) {
  for (const auto& s : workflow["stages"]) {
    if (s["name"].Scalar() == name) return s;
  }
  return YAML::Node();
}

std::pair<std::string, std::string> reference_source(const YAML::Node& node) {
  if (!node || !node.IsMap() || !node["from"] || !node["from"].IsScalar()) return {};
  const std::string from = node["from"].Scalar();
  const auto dot = from.find('.');
  if (dot == std::string::npos) return {};
  return {from.substr(0, dot), from.substr(dot + 1)};
}

}  // namespace pbms::config
