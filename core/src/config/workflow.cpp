#include "pbms/config/workflow.hpp"
#include "pbms/driver/checkpoint_plan.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pbms/config/stage_names.hpp"
#include "pbms/config/validator.hpp"
#include "pbms/config/yaml_source.hpp"

namespace pbms::config {
namespace {

std::vector<std::string> all_kinds(const std::vector<DriverDescription>& drivers) {
  std::vector<std::string> out;
  for (const auto& d : drivers) {
    for (const auto& s : d.stage_kinds) {
      if (!s.internal) out.push_back(s.kind);
    }
  }
  return out;
}

const StageKindSpec* find_kind(const std::vector<DriverDescription>& drivers,
                               const std::string& kind) {
  for (const auto& d : drivers) {
    if (const auto* s = d.stage_kind(kind)) return s;
  }
  return nullptr;
}

std::string_view shape_phrase(OutputSpec::Shape shape) {
  switch (shape) {
    case OutputSpec::Shape::kTable:
      return "a table";
    case OutputSpec::Shape::kMap:
      return "a map";
    case OutputSpec::Shape::kScalar:
      break;
  }
  return "a single number";
}

// The first stage that names each material.
std::map<std::string, int> first_stage_using(const std::vector<Reference>& refs) {
  std::map<std::string, int> first;
  for (const auto& r : refs) {
    if (r.type != Reference::Target::kMaterial || r.key_path.rfind("stages[", 0) != 0) continue;
    const int idx = std::stoi(r.key_path.substr(7));
    const auto it = first.find(r.target);
    if (it == first.end() || idx < it->second) first[r.target] = idx;
  }
  return first;
}

// The stage a key belongs to: "stages[i]..." is stage i; a key inside
// "materials.<name>" belongs to the first stage that uses that material,
// since that stage is the first to need it resolved. -1: no stage.
int stage_index_of(const std::string& key_path, const std::map<std::string, int>& first_use) {
  if (key_path.rfind("stages[", 0) == 0) return std::stoi(key_path.substr(7));
  if (key_path.rfind("materials.", 0) != 0) return -1;
  const std::string rest = key_path.substr(10);
  const auto it = first_use.find(rest.substr(0, rest.find('.')));
  return it == first_use.end() ? -1 : it->second;
}

}  // namespace

std::filesystem::path Workflow::run_dir() const {
  return std::filesystem::path(output_dir) / run_name;
}

std::vector<std::string> Workflow::programs() const {
  std::vector<std::string> out;
  for (const auto& s : stages) {
    for (const auto& d : s.drivers) {
      if (std::find(out.begin(), out.end(), d) == out.end()) out.push_back(d);
    }
  }
  return out;
}

Param materials_schema(const std::vector<DriverDescription>& drivers) {
  std::vector<std::string> kinds;
  for (const auto& d : drivers) {
    for (const auto& m : d.material_kinds) kinds.push_back(m.kind);
  }
  Param material = Param::map(
      "material",
      {Param::choice("kind", kinds, "Interaction model or constitutive model").require()},
      "One material");
  material.discriminated_by("kind");
  for (const auto& d : drivers) {
    for (const auto& m : d.material_kinds) material.variant(m.kind, m.params, m.doc);
  }
  return Param::map_of("materials", material, "Named materials that stages refer to");
}

Param workflow_schema(const std::vector<DriverDescription>& drivers) {
  using units::Dimension;
  std::vector<Param> launch_fields;
  for (const auto& d : drivers) {
    if (d.program == kCouplerProgram) continue;
    launch_fields.push_back(
        Param::integer(d.short_name, fmt::format("MPI ranks for {}", d.program)).def(1).above(0));
  }
  Param stage =
      Param::map("stage",
                 {Param::identifier("name", "Unique stage name; names its results").require(),
                  Param::string("kind", "Stage kind, declared by one of the drivers").require()},
                 "One stage");
  stage.discriminated_by("kind");
  for (const auto& d : drivers) {
    for (const auto& s : d.stage_kinds) {
      if (!s.internal) stage.variant(s.kind, s.params, s.doc);
    }
  }
  return Param::map(
      "workflow",
      {
          Param::map(
              "run",
              {Param::identifier("name", "Run name; results go to <output>/<name>/").require(),
               Param::path("output", "Directory that holds run directories").def("runs"),
               Param::integer("seed", "Seed of every random number in the run")
                   .def(12345)
                   .at_least(0)
                   .at_most(1e18)},
              "Run identity")
              .require(),
          Param::map("launch", launch_fields, "MPI ranks per driver program")
              .def(YAML::Node(YAML::NodeType::Map)),
          materials_schema(drivers).def(YAML::Node(YAML::NodeType::Map)),
          Param::list_of("stages", stage, "Stages, run in order").require().length(1, 1000),
          CheckpointPlan::schema(),
      },
      "A PBMS workflow");
}

namespace {

// load_workflow's steps over one file, each reporting through the
// validator so that every problem is listed at once.
class WorkflowLoader {
 public:
  WorkflowLoader(const std::string& path, const std::vector<DriverDescription>& drivers)
      : path_(path), drivers_(drivers), v_(path) {}

  LoadResult load() {
    LoadResult result;
    if (!read_root(result)) return result;
    resolved_ = v_.check(workflow_schema(drivers_), root_, "");
    check_run_directory();
    check_checkpoint();
    collect_stages();
    check_references();
    read_held_files();
    if (v_.errors().empty() && file_errors_.empty()) run_stage_checks();
    result.errors = v_.errors();
    result.errors.insert(result.errors.end(), file_errors_.begin(), file_errors_.end());
    result.warnings = v_.warnings();
    if (result.errors.empty()) {
      result.workflow = workflow();
      for (const auto& w : result.warnings) result.workflow->warnings.push_back(w.format());
    }
    return result;
  }

 private:
  // The file as a YAML map; false (with the errors in `result`) otherwise.
  bool read_root(LoadResult& result) {
    if (!std::filesystem::exists(path_)) {
      result.errors.push_back(
          {path_, 0, 0, "", "cannot open the workflow file: it does not exist"});
      return false;
    }
    std::optional<YAML::Node> loaded = load_yaml_source(path_, v_, "a workflow");
    if (!loaded) {
      result.errors = v_.errors();
      return false;
    }
    root_ = *loaded;
    if (!root_.IsMap()) {
      YAML::Mark top;
      top.line = 0;
      top.column = 0;
      v_.error_at(root_.Mark().is_null() ? top : root_.Mark(), "",
                  "expected a map with keys run, launch, materials, stages");
      result.errors = v_.errors();
      return false;
    }
    return true;
  }

  // A checkpoint map must say when, and some stage must write them.
  void check_checkpoint() {
    const YAML::Node c = root_["checkpoint"];
    if (!c || !c.IsMap()) return;
    if (!c["every_steps"] && !c["every_minutes"]) {
      v_.error(c, "checkpoint", "say when to write one: every_steps, every_minutes or both");
      return;
    }
    std::vector<std::string> writers;
    for (const auto& d : drivers_) {
      for (const auto& k : d.stage_kinds) {
        if (k.checkpoints) writers.push_back(k.kind);
      }
    }
    for (const auto& s : root_["stages"]) {
      if (s.IsMap() && s["kind"] &&
          std::find(writers.begin(), writers.end(), s["kind"].Scalar()) != writers.end()) {
        return;
      }
    }
    v_.warn(c, "checkpoint",
            fmt::format("no stage of this workflow writes checkpoints (only {} do): a resumed "
                        "run keeps the finished stages and starts the others again",
                        fmt::join(writers, ", ")));
  }

  // The run directory must be possible: nothing in the way (a file where a
  // directory should be) and a parent it can be created in.
  void check_run_directory() {
    const YAML::Node run_out = resolved_["run"];
    if (!run_out.IsMap() || !run_out["name"] || !run_out["output"]) return;
    const std::filesystem::path dir =
        std::filesystem::path(run_out["output"].Scalar()) / run_out["name"].Scalar();
    if (const std::string problem = directory_problem(dir); !problem.empty()) {
      const YAML::Node at = root_["run"]["output"] ? root_["run"]["output"] : root_["run"];
      v_.error(at, "run.output",
               fmt::format("the run directory '{}' cannot be created: {}",
                           clipped(dir.string(), 300), problem));
    }
  }

  // Stage names (each once) and kinds (declared by a driver, not internal).
  void collect_stages() {
    stages_ = root_["stages"];
    if (!stages_.IsSequence()) return;
    for (size_t i = 0; i < stages_.size(); ++i) {
      const YAML::Node st = stages_[i];
      const std::string sp = fmt::format("stages[{}]", i);
      std::string name;
      if (st.IsMap() && st["name"] && st["name"].IsScalar()) {
        name = st["name"].Scalar();
        if (std::find(stage_names_.begin(), stage_names_.end(), name) != stage_names_.end()) {
          v_.error(st["name"], sp + ".name", fmt::format("stage name '{}' is used twice", name));
        }
      }
      const StageKindSpec* spec = nullptr;
      if (st.IsMap() && st["kind"] && st["kind"].IsScalar()) spec = stage_kind(st["kind"], sp);
      stage_names_.push_back(name);
      stage_specs_.push_back(spec);
    }
  }

  const StageKindSpec* stage_kind(const YAML::Node& kind_node, const std::string& sp) {
    const std::string& kind = kind_node.Scalar();
    const StageKindSpec* spec = find_kind(drivers_, kind);
    if (!spec) {
      const auto kinds = all_kinds(drivers_);
      v_.error(kind_node, sp + ".kind",
               fmt::format("unknown stage kind '{}': no installed driver declares it "
                           "(declared: {}){}",
                           clipped(kind), fmt::join(kinds, ", "), suggest(kind, kinds)));
      return nullptr;
    }
    if (spec->internal) {
      v_.error(kind_node, sp + ".kind",
               fmt::format("stage kind '{}' is a part of another kind that the coupler starts "
                           "itself ({}); a workflow cannot name it",
                           kind, spec->doc));
      return nullptr;
    }
    return spec;
  }

  // Cross references: stage outputs must come from earlier stages;
  // materials must exist and suit the stage.
  void check_references() {
    const std::map<std::string, int> first_use = first_stage_using(v_.references());
    for (const auto& r : v_.references()) {
      YAML::Mark m;
      m.line = r.line - 1;
      m.column = r.column - 1;
      const int idx = stage_index_of(r.key_path, first_use);
      if (r.type == Reference::Target::kMaterial) {
        check_material_reference(r, m, idx);
      } else if (r.type == Reference::Target::kStage) {
        check_stage_reference(r, m, idx);
      } else if (r.type == Reference::Target::kStageOutput) {
        check_output_reference(r, m, idx);
      }
    }
    check_stage_names(v_.references(), v_);
  }

  void check_material_reference(const Reference& r, const YAML::Mark& m, int idx) {
    const YAML::Node materials = root_["materials"];
    if (!materials.IsMap() || !materials[r.target]) {
      v_.error_at(m, r.key_path,
                  fmt::format("material '{}' is not defined under 'materials'", clipped(r.target)));
      return;
    }
    const YAML::Node mk = materials[r.target]["kind"];
    if (idx < 0 || !stage_specs_[idx] || !mk || !mk.IsScalar()) return;
    const auto& ok = stage_specs_[idx]->material_kinds;
    if (std::find(ok.begin(), ok.end(), mk.Scalar()) == ok.end()) {
      v_.error_at(m, r.key_path,
                  fmt::format("material '{}' is of kind '{}', but stage kind '{}' takes {}",
                              r.target, mk.Scalar(), stage_specs_[idx]->kind, fmt::join(ok, ", ")));
    }
  }

  void check_stage_reference(const Reference& r, const YAML::Mark& m, int idx) {
    const int target_idx = earlier_stage(r.target, idx, m, r.key_path, "name");
    const StageKindSpec* spec = target_idx >= 0 ? stage_specs_[target_idx] : nullptr;
    if (spec && std::find(r.kinds.begin(), r.kinds.end(), spec->kind) == r.kinds.end()) {
      v_.error_at(m, r.key_path,
                  fmt::format("stage '{}' is a {} stage; this key takes a stage of kind {}",
                              r.target, spec->kind, fmt::join(r.kinds, " or ")));
    }
  }

  void check_output_reference(const Reference& r, const YAML::Mark& m, int idx) {
    const auto dot = r.target.find('.');
    if (dot == std::string::npos) {
      v_.error_at(
          m, r.key_path,
          fmt::format("'{}' is not a stage output: write <stage>.<output>", clipped(r.target)));
      return;
    }
    const std::string sname = r.target.substr(0, dot);
    const std::string oname = r.target.substr(dot + 1);
    const int target_idx = earlier_stage(sname, idx, m, r.key_path, "use outputs of");
    if (target_idx < 0) return;
    const StageKindSpec* spec = stage_specs_[target_idx];
    if (!spec) return;
    const OutputSpec* out = spec->output(oname);
    if (!out) {
      std::vector<std::string> names;
      for (const auto& o : spec->outputs) names.push_back(o.name);
      v_.error_at(
          m, r.key_path,
          fmt::format("stage '{}' ({}) has no output '{}' (outputs: {}){}", sname, spec->kind,
                      clipped(oname), fmt::join(names, ", "), suggest(oname, names)));
    } else if (out->shape != r.wants) {
      v_.error_at(m, r.key_path,
                  fmt::format("output '{}' is {}; this key takes {}", r.target,
                              shape_phrase(out->shape), shape_phrase(r.wants)));
    }
  }

  // The index of stage `name`, which must run before stage `idx` (-1: no
  // stage); -1 after reporting that it does not.
  int earlier_stage(const std::string& name, int idx, const YAML::Mark& m,
                    const std::string& key_path, std::string_view use) {
    const auto it = std::find(stage_names_.begin(), stage_names_.end(), name);
    if (it == stage_names_.end()) {
      v_.error_at(
          m, key_path,
          fmt::format("no stage is named '{}'{}", clipped(name), suggest(name, stage_names_)));
      return -1;
    }
    const int target_idx = static_cast<int>(it - stage_names_.begin());
    if (idx >= 0 && target_idx >= idx) {
      v_.error_at(m, key_path,
                  fmt::format("stage '{}' runs {} this one: a stage can only {} stages before it",
                              name, target_idx == idx ? "as" : "after", use));
      return -1;
    }
    return target_idx;
  }

  // A material key may be given inline or as a file of the same format
  // (Param::holds: a dpd_mesoparticle's potential and potential_file); a
  // file is checked here, with its own line numbers, and takes the key's
  // place in the resolved materials.
  void read_held_files() {
    const YAML::Node materials = root_["materials"];
    if (!materials.IsMap()) return;
    for (const auto& entry : materials) {
      const YAML::Node m = entry.second;
      if (!m.IsMap() || !m["kind"] || !m["kind"].IsScalar()) continue;
      const MaterialKindSpec* kind = find_material_kind(drivers_, m["kind"].Scalar());
      if (!kind) continue;  // already reported
      for (const Param& file : kind->params) {
        if (!file.holds.empty()) read_held_file(entry.first.as<std::string>(), m, *kind, file);
      }
    }
  }

  void read_held_file(const std::string& name, const YAML::Node& m, const MaterialKindSpec& kind,
                      const Param& file_param) {
    const std::string& key = file_param.holds;
    const std::string& file_key = file_param.name;
    const std::string mp = "materials." + name;
    if (m[key] && m[file_key]) {
      v_.error(m[file_key], mp + "." + file_key,
               fmt::format("give `{}` or `{}`, not both", key, file_key));
      return;
    }
    if (!m[key] && !m[file_key]) {
      v_.error(m, mp, fmt::format("a {} needs `{}` (inline) or `{}`", kind.kind, key, file_key));
      return;
    }
    if (!m[file_key]) return;
    const YAML::Node file_node = resolved_["materials"][name][file_key];
    if (!file_node || !file_node.IsScalar()) return;  // already reported
    const std::string& file = file_node.Scalar();
    const Param* held = nullptr;
    for (const Param& p : kind.params) {
      if (p.name == key) held = &p;
    }
    if (!held) return;
    Validator fv(file);
    const std::optional<YAML::Node> doc = load_yaml_source(file, fv, fmt::format("a {} file", key));
    if (doc) {
      YAML::Node checked = fv.check(*held, *doc, key);
      if (fv.errors().empty()) resolved_["materials"][name][key] = checked;
    }
    file_errors_.insert(file_errors_.end(), fv.errors().begin(), fv.errors().end());
  }

  // Checks a stage kind declares beside its code, once everything they
  // read is known to be sound.
  void run_stage_checks() {
    for (size_t i = 0; i < stage_specs_.size(); ++i) {
      if (!stage_specs_[i] || !stage_specs_[i]->check) continue;
      const std::string sp = fmt::format("stages[{}]", i);
      stage_specs_[i]->check({v_, stages_[i], resolved_["stages"][i], sp, resolved_["materials"],
                              drivers_, resolved_});
    }
  }

  Workflow workflow() const {
    Workflow wf;
    wf.source_file = path_;
    wf.resolved = resolved_;
    wf.run_name = resolved_["run"]["name"].as<std::string>();
    wf.run_name_line = root_["run"]["name"].Mark().line + 1;
    wf.run_name_column = root_["run"]["name"].Mark().column + 1;
    wf.output_dir = resolved_["run"]["output"].as<std::string>();
    wf.seed = resolved_["run"]["seed"].as<uint64_t>();
    wf.materials = resolved_["materials"];
    for (size_t i = 0; i < stage_specs_.size(); ++i) wf.stages.push_back(stage_config(i));
    for (const auto& prog : wf.programs()) {
      for (const auto& d : drivers_) {
        if (d.program == prog) wf.ranks[prog] = resolved_["launch"][d.short_name].as<int>(1);
      }
    }
    return wf;
  }

  StageConfig stage_config(size_t i) const {
    const StageKindSpec& spec = *stage_specs_[i];
    StageConfig sc;
    sc.name = stage_names_[i];
    sc.kind = spec.kind;
    sc.program = spec.program;
    sc.drivers = sc.program == kCouplerProgram ? spec.uses : std::vector<std::string>{sc.program};
    for (const auto& partner : spec.partners) sc.drivers.push_back(partner.program);
    sc.params = resolved_["stages"][i];
    sc.line = stages_[i].Mark().line + 1;
    return sc;
  }

  std::string path_;
  const std::vector<DriverDescription>& drivers_;
  Validator v_;
  YAML::Node root_;  // not const: a const lookup of a missing key throws
  YAML::Node resolved_;
  YAML::Node stages_;
  std::vector<std::string> stage_names_;
  std::vector<const StageKindSpec*> stage_specs_;
  std::vector<ConfigError> file_errors_;
};

}  // namespace

LoadResult load_workflow(const std::string& path, const std::vector<DriverDescription>& drivers) {
  return WorkflowLoader(path, drivers).load();
}

std::string apply_rank_override(Workflow& wf, const std::vector<DriverDescription>& drivers,
                                const std::string& spec) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos) {
    return fmt::format("--ranks '{}': write PROGRAM=COUNT, e.g. md=2", spec);
  }
  const std::string name = spec.substr(0, eq);
  int count = 0;
  try {
    size_t used = 0;
    count = std::stoi(spec.substr(eq + 1), &used);
    if (used != spec.size() - eq - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    return fmt::format("--ranks '{}': '{}' is not an integer", spec, spec.substr(eq + 1));
  }
  if (count < 1) return fmt::format("--ranks '{}': the rank count must be at least 1", spec);
  for (const auto& d : drivers) {
    if (d.program == kCouplerProgram) continue;
    if (d.short_name == name || d.program == name) {
      const auto progs = wf.programs();
      if (std::find(progs.begin(), progs.end(), d.program) != progs.end()) {
        wf.ranks[d.program] = count;
      }
      wf.resolved["launch"][d.short_name] = count;
      return {};
    }
  }
  std::vector<std::string> names;
  for (const auto& d : drivers) names.push_back(d.short_name);
  return fmt::format("--ranks '{}': no driver is called '{}' (drivers: {})", spec, name,
                     fmt::join(names, ", "));
}

}  // namespace pbms::config
