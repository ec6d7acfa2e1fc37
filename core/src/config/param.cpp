#include "pbms/config/param.hpp"

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::config {
namespace {

struct KindName {
  ParamKind kind;
  std::string_view name;
};
constexpr KindName kKindNames[] = {
    {ParamKind::kInteger, "integer"},
    {ParamKind::kReal, "real"},
    {ParamKind::kBoolean, "boolean"},
    {ParamKind::kString, "string"},
    {ParamKind::kName, "name"},
    {ParamKind::kFile, "file"},
    {ParamKind::kPath, "path"},
    {ParamKind::kChoice, "choice"},
    {ParamKind::kRealList, "real list"},
    {ParamKind::kIntList, "integer list"},
    {ParamKind::kMap, "map"},
    {ParamKind::kMapOf, "named map"},
    {ParamKind::kListOf, "list"},
    {ParamKind::kTable, "table"},
};

constexpr std::pair<units::Dimension, std::string_view> kDimNames[] = {
    {units::Dimension::kNone, "none"},
    {units::Dimension::kPressure, "pressure"},
    {units::Dimension::kLength, "length"},
    {units::Dimension::kTime, "time"},
    {units::Dimension::kTemperature, "temperature"},
    {units::Dimension::kVelocity, "velocity"},
    {units::Dimension::kEnergy, "energy"},
    {units::Dimension::kMass, "mass"},
    {units::Dimension::kRate, "rate"},
    {units::Dimension::kDensity, "density"},
    {units::Dimension::kAcceleration, "acceleration"},
    {units::Dimension::kForce, "force"},
    {units::Dimension::kSurfaceEnergy, "surface_energy"},
};

Param make(std::string name, ParamKind kind, std::string doc) {
  Param p;
  p.name = std::move(name);
  p.kind = kind;
  p.doc = std::move(doc);
  return p;
}

}  // namespace

std::string_view kind_name(ParamKind k) {
  for (const auto& kn : kKindNames) {
    if (kn.kind == k) return kn.name;
  }
  return "?";
}

Param Param::integer(std::string n, std::string d) {
  return make(std::move(n), ParamKind::kInteger, std::move(d));
}
Param Param::real(std::string n, units::Dimension dim, std::string d) {
  Param p = make(std::move(n), ParamKind::kReal, std::move(d));
  p.dimension = dim;
  return p;
}
Param Param::boolean(std::string n, std::string d) {
  return make(std::move(n), ParamKind::kBoolean, std::move(d));
}
Param Param::string(std::string n, std::string d) {
  return make(std::move(n), ParamKind::kString, std::move(d));
}
Param Param::identifier(std::string n, std::string d) {
  return make(std::move(n), ParamKind::kName, std::move(d));
}
Param Param::file(std::string n, std::string d) {
  return make(std::move(n), ParamKind::kFile, std::move(d));
}
Param Param::path(std::string n, std::string d) {
  return make(std::move(n), ParamKind::kPath, std::move(d));
}
Param Param::choice(std::string n, std::vector<std::string> c, std::string d) {
  Param p = make(std::move(n), ParamKind::kChoice, std::move(d));
  p.choices = std::move(c);
  return p;
}
Param Param::real_list(std::string n, units::Dimension dim, std::string d) {
  Param p = make(std::move(n), ParamKind::kRealList, std::move(d));
  p.dimension = dim;
  return p;
}
Param Param::int_list(std::string n, std::string d) {
  return make(std::move(n), ParamKind::kIntList, std::move(d));
}
Param Param::map(std::string n, std::vector<Param> f, std::string d) {
  Param p = make(std::move(n), ParamKind::kMap, std::move(d));
  p.fields = std::move(f);
  return p;
}
Param Param::map_of(std::string n, Param element, std::string d) {
  Param p = make(std::move(n), ParamKind::kMapOf, std::move(d));
  p.fields.push_back(std::move(element));
  return p;
}
Param Param::list_of(std::string n, Param element, std::string d) {
  Param p = make(std::move(n), ParamKind::kListOf, std::move(d));
  p.fields.push_back(std::move(element));
  return p;
}

Param Param::table(std::string n, std::string d) {
  Param p = make(std::move(n), ParamKind::kTable, std::move(d));
  p.allow_reference = true;
  return p;
}

Param& Param::variant(const std::string& value, std::vector<Param> extra, std::string d) {
  variants[value] = std::move(extra);
  variant_docs[value] = std::move(d);
  return *this;
}

const Param* Param::field(std::string_view key) const {
  for (const auto& f : fields) {
    if (f.name == key) return &f;
  }
  return nullptr;
}

std::vector<const Param*> Param::fields_for(const std::string& v) const {
  std::vector<const Param*> out;
  for (const auto& f : fields) out.push_back(&f);
  if (auto it = variants.find(v); it != variants.end()) {
    for (const auto& f : it->second) out.push_back(&f);
  }
  return out;
}

std::string Param::type_text() const {
  std::string t(kind_name(kind));
  if ((kind == ParamKind::kReal || kind == ParamKind::kRealList) &&
      dimension != units::Dimension::kNone) {
    t += fmt::format(" [{}]", units::canonical_symbol(dimension));
  }
  if (kind == ParamKind::kChoice) t += fmt::format(" ({})", fmt::join(choices, " | "));
  if (allow_auto) t += " or auto";
  return t;
}

YAML::Node to_yaml(const Param& p) {
  YAML::Node n;
  n["name"] = p.name;
  n["kind"] = std::string(kind_name(p.kind));
  if (!p.doc.empty()) n["doc"] = p.doc;
  for (const auto& [dim, name] : kDimNames) {
    if (dim == p.dimension && dim != units::Dimension::kNone) n["dimension"] = std::string(name);
  }
  if (p.required) n["required"] = true;
  if (p.default_value) n["default"] = YAML::Clone(*p.default_value);
  if (p.min) {
    n["min"] = *p.min;
    if (p.min_exclusive) n["min_exclusive"] = true;
  }
  if (p.max) {
    n["max"] = *p.max;
    if (p.max_exclusive) n["max_exclusive"] = true;
  }
  if (!p.holds.empty()) n["holds"] = p.holds;
  if (p.min_length) n["min_length"] = *p.min_length;
  if (p.max_length) n["max_length"] = *p.max_length;
  if (!p.lengths.empty()) n["lengths"] = p.lengths;
  if (!p.choices.empty()) n["choices"] = p.choices;
  if (p.allow_reference) n["referable"] = true;
  if (p.names_material) n["material"] = true;
  if (p.allow_auto) n["or_auto"] = true;
  if (!p.stage_kinds.empty()) n["stage_kinds"] = p.stage_kinds;
  if (!p.entry_lists.empty()) n["entry_of"] = p.entry_lists;
  if (p.declares_names) n["declares_names"] = true;
  if (!p.lower_upper.first.empty()) {
    n["bounds"].push_back(p.lower_upper.first);
    n["bounds"].push_back(p.lower_upper.second);
  }
  if (!p.excludes.empty()) n["not_with"] = p.excludes;
  if (p.one_key) n["one_key"] = true;
  if (!p.only_with.first.empty()) {
    n["only_with"]["key"] = p.only_with.first;
    n["only_with"]["value"] = p.only_with.second;
  }
  if (!p.required_with.first.empty()) {
    n["required_with"]["key"] = p.required_with.first;
    n["required_with"]["value"] = p.required_with.second;
  }
  for (const auto& f : p.fields) n["fields"].push_back(to_yaml(f));
  if (!p.discriminator.empty()) n["discriminator"] = p.discriminator;
  for (const auto& [v, fs] : p.variants) {
    YAML::Node vn;
    vn["value"] = v;
    vn["doc"] = p.variant_docs.at(v);
    for (const auto& f : fs) vn["fields"].push_back(to_yaml(f));
    n["variants"].push_back(vn);
  }
  return n;
}

Param param_from_yaml(const YAML::Node& n) {
  Param p;
  p.name = n["name"].as<std::string>();
  const auto kind = n["kind"].as<std::string>();
  bool found = false;
  for (const auto& kn : kKindNames) {
    if (kn.name == kind) {
      p.kind = kn.kind;
      found = true;
    }
  }
  if (!found) throw Error(fmt::format("unknown parameter kind '{}' in a schema", kind));
  if (n["doc"]) p.doc = n["doc"].as<std::string>();
  if (n["dimension"]) {
    const auto dim = n["dimension"].as<std::string>();
    for (const auto& [d, name] : kDimNames) {
      if (name == dim) p.dimension = d;
    }
  }
  p.required = n["required"] && n["required"].as<bool>();
  if (n["default"]) p.default_value = YAML::Clone(n["default"]);
  if (n["min"]) p.min = n["min"].as<double>();
  p.min_exclusive = n["min_exclusive"] && n["min_exclusive"].as<bool>();
  if (n["max"]) p.max = n["max"].as<double>();
  p.max_exclusive = n["max_exclusive"] && n["max_exclusive"].as<bool>();
  if (n["holds"]) p.holds = n["holds"].as<std::string>();
  if (n["min_length"]) p.min_length = n["min_length"].as<size_t>();
  if (n["max_length"]) p.max_length = n["max_length"].as<size_t>();
  if (n["lengths"]) p.lengths = n["lengths"].as<std::vector<size_t>>();
  if (n["choices"]) p.choices = n["choices"].as<std::vector<std::string>>();
  p.allow_reference = n["referable"] && n["referable"].as<bool>();
  p.names_material = n["material"] && n["material"].as<bool>();
  p.allow_auto = n["or_auto"] && n["or_auto"].as<bool>();
  if (n["stage_kinds"]) p.stage_kinds = n["stage_kinds"].as<std::vector<std::string>>();
  if (n["entry_of"]) p.entry_lists = n["entry_of"].as<std::vector<std::string>>();
  p.declares_names = n["declares_names"] && n["declares_names"].as<bool>();
  if (n["bounds"]) p.lower_upper = {n["bounds"][0].Scalar(), n["bounds"][1].Scalar()};
  if (n["not_with"]) p.excludes = n["not_with"].as<std::string>();
  p.one_key = n["one_key"] && n["one_key"].as<bool>();
  if (n["only_with"]) {
    p.only_with = {n["only_with"]["key"].as<std::string>(),
                   n["only_with"]["value"].as<std::string>()};
  }
  if (n["required_with"]) {
    p.required_with = {n["required_with"]["key"].as<std::string>(),
                       n["required_with"]["value"].as<std::string>()};
  }
  for (const auto& f : n["fields"]) p.fields.push_back(param_from_yaml(f));
  if (n["discriminator"]) p.discriminator = n["discriminator"].as<std::string>();
  for (const auto& vn : n["variants"]) {
    std::vector<Param> fs;
    for (const auto& f : vn["fields"]) fs.push_back(param_from_yaml(f));
    p.variant(vn["value"].as<std::string>(), std::move(fs), vn["doc"].as<std::string>(""));
  }
  return p;
}

}  // namespace pbms::config
