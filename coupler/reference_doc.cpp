#include "reference_doc.hpp"

#include <fmt/format.h>

#include "pbms/config/workflow.hpp"

namespace pbms::coupler {
namespace {

std::string scalar_text(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

std::string cell(std::string s) {
  for (auto& c : s) {
    if (c == '|') c = '/';
    if (c == '\n') c = ' ';
  }
  return s;
}

// A region key (block, sphere, cylinder or a combination): described once,
// in the reference's own section, not under every key that holds one.
bool is_region(const config::Param& p) {
  return p.kind == config::ParamKind::kMap && p.discriminator == "style" &&
         p.variants.count("block") > 0;
}

// A list's or named map's type says what each entry is: `list of map` has
// its own table below, `list of choice (x | y | z)` does not need one.
std::string type_cell(const config::Param& p) {
  using config::ParamKind;
  const bool container = p.kind == ParamKind::kListOf || p.kind == ParamKind::kMapOf;
  if (!container || p.fields.empty()) return p.type_text();
  return fmt::format("{} of {}", p.type_text(), p.fields[0].type_text());
}

void table(std::string& out, const std::vector<const config::Param*>& fields) {
  out += "| key | type | default | description |\n|---|---|---|---|\n";
  for (const auto* p : fields) {
    std::string def = p->required        ? "**required**"
                      : p->default_value ? fmt::format("`{}`", scalar_text(*p->default_value))
                                         : "—";
    std::string doc = p->doc;
    if (!doc.empty() && doc.back() != '.') doc += '.';
    if (p->min) doc += fmt::format(" Must be {} {}.", p->min_exclusive ? ">" : "≥", *p->min);
    if (p->max) doc += fmt::format(" Must be {} {}.", p->max_exclusive ? "<" : "≤", *p->max);
    if (p->allow_reference) doc += " May be `{from: <stage>.<output>}`.";
    if (p->names_material) doc += " Names an entry of `materials`.";
    if (!p->entry_lists.empty()) {
      doc += fmt::format(" Names an entry of this stage's {}.", fmt::join(p->entry_lists, " or "));
    }
    if (p->declares_names) doc += " Entry names are this stage's, shared by bodies and groups.";
    if (!p->stage_kinds.empty()) {
      doc += fmt::format(" Names an earlier stage of kind {}.", fmt::join(p->stage_kinds, " or "));
    }
    if (p->one_key) doc += " Takes exactly one of its keys.";
    if (is_region(*p)) doc += " A region: see [Regions](#regions).";
    if (!p->excludes.empty()) doc += fmt::format(" Not given together with `{}`.", p->excludes);
    if (!p->required_with.first.empty()) {
      doc +=
          fmt::format(" Required with `{}: {}`.", p->required_with.first, p->required_with.second);
    }
    if (!p->only_with.first.empty()) {
      doc += fmt::format(" Only with `{}: {}`.", p->only_with.first, p->only_with.second);
    }
    if (p->kind == config::ParamKind::kReal || p->kind == config::ParamKind::kRealList) {
      if (p->dimension != units::Dimension::kNone) {
        doc += fmt::format(" Accepts units: {}.", units::accepted_symbols(p->dimension));
      }
    }
    out += fmt::format("| `{}` | {} | {} | {} |\n", p->name, cell(type_cell(*p)), cell(def),
                       cell(doc));
  }
  out += "\n";
}

std::vector<const config::Param*> ptrs(const std::vector<config::Param>& v) {
  std::vector<const config::Param*> out;
  for (const auto& p : v) out.push_back(&p);
  return out;
}

// The map a key holds, itself or as each entry of a list or named map.
const config::Param* map_of(const config::Param& p) {
  using config::ParamKind;
  if (p.kind == ParamKind::kMap) return &p;
  const bool container = p.kind == ParamKind::kListOf || p.kind == ParamKind::kMapOf;
  if (container && !p.fields.empty() && p.fields[0].kind == ParamKind::kMap) return &p.fields[0];
  return nullptr;
}

std::string entry_path(const std::string& prefix, const config::Param& p) {
  const std::string base = prefix.empty() ? p.name : prefix + "." + p.name;
  if (p.kind == config::ParamKind::kListOf) return base + "[]";
  if (p.kind == config::ParamKind::kMapOf) return base + ".<name>";
  return base;
}

// A table per nested map below `fields`, and per variant of a map with a
// discriminator (a region's style), down to `depth` levels: a region nests
// regions, and three levels show every key.
void nested_tables(std::string& out, const std::string& prefix,
                   const std::vector<const config::Param*>& fields, int depth) {
  if (depth == 0) return;
  for (const auto* f : fields) {
    const config::Param* m = map_of(*f);
    if (!m || is_region(*m)) continue;
    const std::string path = entry_path(prefix, *f);
    if (m->discriminator.empty()) {
      if (m->fields.empty()) continue;
      out += fmt::format("#### `{}`\n\n", path);
      table(out, ptrs(m->fields));
      nested_tables(out, path, ptrs(m->fields), depth - 1);
      continue;
    }
    for (const auto& [variant, extra] : m->variants) {
      const auto all = m->fields_for(variant);
      out += fmt::format("#### `{}` with `{}: {}`\n\n", path, m->discriminator, variant);
      table(out, all);
      nested_tables(out, path, all, depth - 1);
    }
  }
}

}  // namespace

// The first region key among the stage kinds' keys, searched depth-first.
const config::Param* find_region(const std::vector<const config::Param*>& fields) {
  for (const auto* f : fields) {
    if (is_region(*f)) return f;
    const config::Param* m = map_of(*f);
    if (!m || m == f) {
      if (m) {
        if (const auto* r = find_region(ptrs(m->fields))) return r;
      }
      continue;
    }
    if (is_region(*m)) return m;
    if (const auto* r = find_region(ptrs(m->fields))) return r;
  }
  return nullptr;
}

void regions_section(std::string& out, const config::Param& region) {
  out +=
      "## Regions\n\nA region is a map whose `style` picks its shape; `union`, `intersection` "
      "and `difference` combine the regions listed in `of`, each one a region again. Lengths "
      "in Å.\n\n";
  for (const auto& [style, extra] : region.variants) {
    out += fmt::format("### region style `{}`\n\n", style);
    table(out, region.fields_for(style));
  }
}

std::string config_reference_markdown(const std::vector<config::DriverDescription>& drivers) {
  const auto schema = config::workflow_schema(drivers);
  std::string out =
      "# Workflow configuration reference\n\n"
      "Generated by `build/bin/coupler reference` from the schema that validates every\n"
      "workflow; the test `config_reference_is_current` fails if this file is stale.\n"
      "Regenerate it with `./pbms reference > docs/config-reference.md`.\n\n"
      "Quantities are in LAMMPS `metal` units (Å, ps, eV, g/mol, bar, K). A real-valued key\n"
      "also takes a string with a unit, e.g. `pressures: [0, \"5 GPa\"]` or `timestep: 2 fs`.\n"
      "Unknown keys, a key given twice, numbers that are not finite (`.nan`, `.inf`) and\n"
      "integers beyond 2147483647 (unless a key states its own bound) are errors. A workflow\n"
      "(and a potential file) is one YAML document of at most 1 MiB, with lines of at most\n"
      "64 KiB; anchors and aliases are fine, recursive ones are not. YAML merge keys copy a\n"
      "map's keys into another (`- <<: *base` then the keys that differ), as\n"
      "`configs/concurrent_impact.yaml` writes its variants.\n\n";
  for (const auto& top : schema.fields) {
    if (top.name == "stages" || top.name == "materials") continue;
    out += fmt::format("## `{}`\n\n{}.\n\n", top.name, top.doc);
    table(out, ptrs(top.fields));
    nested_tables(out, top.name, ptrs(top.fields), 3);
  }
  const auto materials = config::materials_schema(drivers);
  const auto& mat = materials.fields[0];
  out += "## `materials`\n\n" + materials.doc +
         ". Each entry is `<name>: {kind: ..., ...}`; stages name it in their `material` key.\n\n";
  for (const auto& [kind, fields] : mat.variants) {
    out += fmt::format("### material kind `{}`\n\n{}.\n\n", kind, mat.variant_docs.at(kind));
    table(out, mat.fields_for(kind));
    nested_tables(out, kind, mat.fields_for(kind), 3);
  }
  const auto& stage = schema.field("stages")->fields[0];
  out += "## `stages`\n\nAn ordered list; each entry has these keys, plus those of its kind.\n\n";
  table(out, ptrs(stage.fields));
  for (const auto& d : drivers) {
    for (const auto& s : d.stage_kinds) {
      if (s.internal) continue;  // started by the coupler, never written
      out += fmt::format("### stage kind `{}` ({})\n\n{}.\n\n", s.kind, s.program, s.doc);
      for (const auto& partner : s.partners) {
        out += fmt::format("Runs together with {}'s part ({}).\n\n", partner.program, partner.kind);
      }
      table(out, ptrs(s.params));
      nested_tables(out, s.kind, ptrs(s.params), 3);
      if (!s.outputs.empty()) {
        out +=
            "Outputs (scalars go to `summary.yaml` and may be referenced by later stages;\n"
            "tables go to `results.h5`):\n\n| output | shape | unit | description |\n"
            "|---|---|---|---|\n";
        for (const auto& o : s.outputs) {
          out += fmt::format("| `{}` | {} | {} | {} |\n", o.name, config::shape_name(o.shape),
                             o.unit, cell(o.doc));
        }
        out += "\n";
      }
    }
  }
  for (const auto& d : drivers) {
    for (const auto& s : d.stage_kinds) {
      if (const auto* r = find_region(ptrs(s.params))) {
        regions_section(out, *r);
        return out;
      }
    }
  }
  return out;
}

}  // namespace pbms::coupler
