#include "fit/fit_settings.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pbms/config/validator.hpp"
#include "pbms/config/workflow.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::coupler::fit {
namespace {

using config::OutputSpec;
using config::Param;
using units::Dimension;

// A map key that may be left out whole: its default is the map of its
// children's defaults, so the typed settings never guess.
Param defaulted(Param map) {
  YAML::Node d(YAML::NodeType::Map);
  for (const auto& f : map.fields) {
    if (f.default_value) d[f.name] = YAML::Clone(*f.default_value);
  }
  map.default_value = d;
  return map;
}

Param isotherm_param() {
  return Param::map(
      "isotherm",
      {Param::table("table",
                    "The MD isotherm, {from: <md_isotherm stage>.isotherm}: columns pressure "
                    "and volume_per_atom")
           .require(),
       Param::real("weight", Dimension::kNone, "Weight of the isotherm in the objective")
           .def(1.0)
           .at_least(0),
       Param::int_list("held_out",
                       "Rows (0-based) computed and reported but kept out of the objective; "
                       "default every second row from the second")},
      "Target: volume per atom against pressure");
}

Param elastic_param() {
  const auto constant = [](const char* name) {
    return Param::real(name, Dimension::kPressure,
                       fmt::format("Target {} (MD at the fit's T)", name))
        .above(0)
        .referable();
  };
  return Param::map("elastic",
                    {constant("c11"), constant("c12"), constant("c44"),
                     Param::real("weight", Dimension::kNone, "Weight of the elastic constants")
                         .def(1.0)
                         .at_least(0)},
                    "Target: cubic elastic constants of the crystal at the fit's temperature");
}

Param surface_param() {
  return Param::map(
      "surface",
      {Param::real("energy_100", Dimension::kSurfaceEnergy,
                   "Target static (100) surface energy, e.g. MD's `1.345 J/m^2` (Mishin's EAM "
                   "copper); the judge computes the candidate's by dpd_surface_energy")
           .require()
           .above(0)
           .referable(),
       Param::real("weight", Dimension::kNone, "Weight of the surface energy in the objective")
           .def(1.0)
           .at_least(0)},
      "Target: the (100) surface energy, which the bulk targets leave free and a thin rod "
      "feels");
}

Param optimizer_param() {
  return defaulted(Param::map(
      "optimizer",
      {Param::choice("global", {"crs2_lm", "direct_l", "none"},
                     "NLopt global search over the bounds (CRS2 with local mutation, or "
                     "locally biased DIRECT)")
           .def("crs2_lm"),
       Param::choice("local", {"bobyqa", "sbplx", "levenberg_marquardt", "none"},
                     "Local polish from the best point of the global search: NLopt's BOBYQA or "
                     "Sbplx, or Levenberg-Marquardt (Eigen) on the residuals, which uses the "
                     "objective's least-squares form and crosses narrow valleys in a few "
                     "Jacobians")
           .def("bobyqa"),
       Param::integer("global_evaluations", "Evaluation budget of the global search")
           .def(60)
           .at_least(0),
       Param::integer("local_evaluations", "Evaluation budget of the local polish")
           .def(60)
           .at_least(0),
       Param::real("x_tolerance", Dimension::kNone,
                   "Stop when a step changes every parameter by less than this fraction of "
                   "its bounds")
           .def(1e-4)
           .above(0),
       Param::real("f_tolerance", Dimension::kNone, "Stop when the objective changes by less")
           .def(1e-10)
           .above(0),
       Param::boolean("static_prefit",
                      "Judge the global search on the static (0 K) crystal, which costs "
                      "milliseconds; the local polish runs at the fit's temperature")
           .def(false),
       Param::choice("scale", {"linear", "log"},
                     "The search's coordinates: each parameter linear between its bounds, or "
                     "its logarithm (every lower bound > 0), so that bounds spanning decades "
                     "are searched by factors, as evenly at their low end as at their high "
                     "end; x_tolerance is then a fraction of ln(upper/lower)")
           .def("linear")},
      "The optimiser (NLopt), seeded by the run's seed"));
}

Param judge_param() {
  std::vector<Param> keys = config::CrystalSampling::params(2000);
  keys.push_back(Param::integer("seed",
                                "Seed of the judge's DPD runs; the run's seed when left out. "
                                "Targets computed by the DPD engine at the run's seed share its "
                                "noise with the judge there; another seed judges independently")
                     .at_least(0));
  return defaulted(Param::map("judge", std::move(keys),
                              "How dpd_driver samples a candidate's crystal (the keys of "
                              "dpd_isotherm and dpd_elastic, whose requests judge it)"));
}

const Param* style_field(const Param& schema, const std::string& style, const std::string& name) {
  const auto it = schema.variants.find(style);
  if (it == schema.variants.end()) return nullptr;
  for (const auto& f : it->second) {
    if (f.name == name && f.kind == config::ParamKind::kReal) return &f;
  }
  return nullptr;
}

std::vector<std::string> style_parameters(const Param& schema, const std::string& style) {
  std::vector<std::string> out;
  const auto it = schema.variants.find(style);
  if (it == schema.variants.end()) return out;
  for (const auto& f : it->second) {
    if (f.kind == config::ParamKind::kReal) out.push_back(f.name);
  }
  return out;
}

void check_free(const config::StageCheck& c, const YAML::Node& potential) {
  const YAML::Node raw_free = c.raw["free"];
  if (!raw_free || !raw_free.IsMap() || raw_free.size() == 0) {
    c.validator.error(raw_free ? raw_free : c.raw, c.path + ".free",
                      "name at least one free parameter with its bounds [lower, upper]");
    return;
  }
  if (!potential.IsMap() || !potential["style"]) return;  // {from: ...}: known at run time
  const Param* schema = potential_schema(c.drivers);
  if (!schema) return;  // no dpd_driver: the stage kind is refused already
  const std::string style = potential["style"].Scalar();
  const YAML::Node scale = c.resolved["optimizer"]["scale"];
  const bool log_scale = scale && scale.Scalar() == "log";
  for (const auto& kv : raw_free) {
    const std::string name = kv.first.Scalar();
    const std::string path = c.path + ".free." + name;
    if (!style_field(*schema, style, name)) {
      const auto names = style_parameters(*schema, style);
      c.validator.error(kv.first, path,
                        fmt::format("pair style '{}' has no parameter '{}' (it has: {}){}", style,
                                    name, fmt::join(names, ", "), config::suggest(name, names)));
      continue;
    }
    const auto bounds = c.resolved["free"][name].as<std::vector<double>>();
    if (bounds[0] >= bounds[1]) {
      c.validator.error(kv.second, path,
                        fmt::format("lower bound {} is not below upper bound {}: a free "
                                    "parameter needs room (to hold it, leave it out of `free`)",
                                    bounds[0], bounds[1]));
      continue;
    }
    if (log_scale && !(bounds[0] > 0.0)) {
      c.validator.error(kv.second, path,
                        fmt::format("lower bound {} is not above 0, which optimizer.scale: log "
                                    "needs (it searches the parameter's logarithm)",
                                    bounds[0]));
      continue;
    }
    const double start = potential[name].as<double>();
    if (start < bounds[0] || start > bounds[1]) {
      c.validator.error(kv.second, path,
                        fmt::format("the start {} (material '{}') is outside [{}, {}]", start,
                                    c.resolved["material"].Scalar(), bounds[0], bounds[1]));
    }
  }
}

// A fit judged at T > 0 against MD's values at another temperature would
// fit thermal expansion and softening that are not there: md_elastic's
// c11 (no _at_t) is its 0 K value, an md_isotherm has its own temperature.
void check_target_temperatures(const config::StageCheck& c) {
  const double t = c.resolved["temperature"].as<double>();
  if (!(t > 0.0)) return;
  const YAML::Node elastic = c.raw["elastic"];
  for (const char* k : {"c11", "c12", "c44"}) {
    const auto [stage, output] = config::reference_source(elastic ? elastic[k] : YAML::Node());
    const YAML::Node src = stage.empty() ? YAML::Node() : config::stage_named(c.workflow, stage);
    if (!src.IsMap() || src["kind"].Scalar() != "md_elastic" || output != k) continue;
    c.validator.error(elastic[k], fmt::format("{}.elastic.{}", c.path, k),
                      fmt::format("the fit judges at {:g} K, but {}.{} is MD's 0 K value: use "
                                  "{}.{}_at_t",
                                  t, stage, output, stage, output));
  }
  const YAML::Node iso = c.raw["isotherm"];
  const auto [stage, output] =
      config::reference_source(iso && iso.IsMap() ? iso["table"] : YAML::Node());
  const YAML::Node src = stage.empty() ? YAML::Node() : config::stage_named(c.workflow, stage);
  if (!src.IsMap() || !src["temperature"]) return;
  const double md = src["temperature"].as<double>();
  if (std::abs(md - t) > 1.0) {
    c.validator.error(
        iso["table"], c.path + ".isotherm.table",
        fmt::format("the fit judges at {:g} K, but '{}' is MD's isotherm at {:g} K", t, stage, md));
  }
}

// Elastic targets given as numbers: a bare number is bar (metal units), so
// 170 meant as GPa is 1e4 times too small, and a value in bar given as GPa
// 1e4 times too large.
void check_target_magnitudes(const config::StageCheck& c) {
  const YAML::Node raw = c.raw["elastic"];
  if (!raw || !raw.IsMap()) return;
  for (const char* k : {"c11", "c12", "c44"}) {
    if (!raw[k] || !raw[k].IsScalar()) continue;
    const double gpa = c.resolved["elastic"][k].as<double>() / 1.0e4;
    if (gpa >= 1.0 && gpa <= 2000.0) continue;
    c.validator.error(raw[k], fmt::format("{}.elastic.{}", c.path, k),
                      fmt::format("{:g} GPa is no crystal's elastic constant (1 to 2,000 GPa); a "
                                  "bare number is bar: write the unit, e.g. `170 GPa`",
                                  gpa));
  }
}

// The judge's crystal must keep each neighbour shell on one side of the
// cutoff over the whole isotherm (check_cutoff_between_shells, at the
// fit's start, once MD's volumes are known). Before the job only the
// material's own lattice constant is known: a cutoff within a few per cent
// of a shell there is likely to be crossed by the isotherm's compression
// (copper at 10 GPa: about 2 % in length) or by thermal expansion.
void check_cutoff_near_shell(const config::StageCheck& c) {
  const YAML::Node material = c.materials[c.resolved["material"].Scalar()];
  const YAML::Node potential = material ? material["potential"] : YAML::Node();
  if (!potential.IsMap() || !potential["cutoff"] || !material["lattice_constant"]) return;
  if (c.raw["free"] && c.raw["free"].IsMap() && c.raw["free"]["cutoff"]) return;
  if (!c.raw["isotherm"]) return;
  constexpr double kBelow = 0.05, kAbove = 0.02;
  const double cutoff = potential["cutoff"].as<double>();
  const double a = material["lattice_constant"].as<double>();
  for (int n = 1; a * std::sqrt(n / 2.0) * (1.0 - kBelow) <= cutoff; ++n) {
    const double shell = a * std::sqrt(n / 2.0);  // fcc: shell n at a sqrt(n/2)
    if (cutoff > shell * (1.0 + kAbove)) continue;
    c.validator.warn(
        c.raw["material"], c.path + ".material",
        fmt::format("the start potential's cutoff {:g} Å is {:+.1f} % from neighbour shell {} "
                    "({:.3f} Å at the material's lattice constant {:g} Å): the isotherm's "
                    "compression or thermal expansion may carry the shell across it, and the fit "
                    "then stops at its start; a cutoff between two shells, with {:g} % room below "
                    "and {:g} % above, is safe",
                    cutoff, 100.0 * (cutoff / shell - 1.0), n, shell, a, 100.0 * kBelow,
                    100.0 * kAbove));
    return;
  }
}

// A surface energy given as a number: a bare one is eV/Å^2 (metal units), so
// 1.345 meant as J/m^2 is 16 times too large. Metals' (100) faces lie
// between about 0.5 and 4 J/m^2 (Mishin's copper 1.345, EAM nickel 3.44).
void check_surface_target(const config::StageCheck& c) {
  const YAML::Node raw = c.raw["surface"];
  if (!raw || !raw.IsMap()) return;
  const YAML::Node energy = raw["energy_100"];
  if (energy && energy.IsScalar()) {
    const double j =
        c.resolved["surface"]["energy_100"].as<double>() * units::kJoulePerM2PerEvPerA2;
    if (j < 0.05 || j > 10.0) {
      c.validator.error(energy, c.path + ".surface.energy_100",
                        fmt::format("{:g} J/m^2 is no metal's surface energy (0.05 to 10 J/m^2); a "
                                    "bare number is eV/Å^2: write the unit, e.g. `1.345 J/m^2`",
                                    j));
    }
  }
}

// Every target weighed 0 leaves nothing to fit: the objective is 0 wherever
// the optimiser goes.
void check_some_weight(const config::StageCheck& c) {
  for (const char* t : {"isotherm", "elastic", "surface"}) {
    const YAML::Node target = c.resolved[t];
    if (target && target.IsMap() && target["weight"] && target["weight"].as<double>() > 0.0) return;
  }
  if (!c.raw["isotherm"] && !c.raw["elastic"] && !c.raw["surface"]) return;  // reported below
  c.validator.error(c.raw, c.path,
                    "every target has weight 0: give at least one a weight above 0 (weight 0 "
                    "reports a target without fitting it)");
}

void check_group_ranks(const config::StageCheck& c) {
  const YAML::Node g = c.resolved["group_ranks"];
  const YAML::Node dpd = c.workflow["launch"] ? c.workflow["launch"]["dpd"] : YAML::Node();
  if (!g || !g.IsScalar() || !dpd || !dpd.IsScalar()) return;
  if (g.as<int>() <= dpd.as<int>()) return;
  c.validator.error(c.raw["group_ranks"] ? c.raw["group_ranks"] : c.raw, c.path + ".group_ranks",
                    fmt::format("a judge group of {} ranks needs at least that many dpd_driver "
                                "ranks; launch.dpd is {}",
                                g.as<int>(), dpd.as<int>()));
}

void check_fit(const config::StageCheck& c) {
  check_target_temperatures(c);
  check_target_magnitudes(c);
  check_group_ranks(c);
  check_cutoff_near_shell(c);
  check_surface_target(c);
  check_some_weight(c);
  const std::string material = c.resolved["material"].Scalar();
  check_free(c, c.materials[material]["potential"]);
  if (!c.raw["isotherm"] && !c.raw["elastic"] && !c.raw["surface"]) {
    c.validator.error(c.raw, c.path,
                      "the fit has no target: give `isotherm`, `elastic`, `surface` or several");
  }
  const YAML::Node elastic = c.raw["elastic"];
  if (elastic && elastic.IsMap() && !elastic["c11"] && !elastic["c12"] && !elastic["c44"]) {
    c.validator.error(elastic, c.path + ".elastic", "give at least one of c11, c12, c44");
  }
  const YAML::Node iso = c.resolved["isotherm"];
  const YAML::Node held = iso ? iso["held_out"] : YAML::Node();
  if (held && held.IsSequence()) {
    for (size_t i = 0; i < held.size(); ++i) {
      if (held[i].as<int>() < 0) {
        c.validator.error(c.raw["isotherm"]["held_out"][i],
                          fmt::format("{}.isotherm.held_out[{}]", c.path, i),
                          "a row index cannot be negative");
      }
    }
  }
}

// A column of a resolved table reference, in metal units.
std::vector<double> column_from_yaml(const YAML::Node& table, const std::string& name,
                                     const std::string& alternative = "") {
  YAML::Node c = table[name];
  if (!c && !alternative.empty()) c = table[alternative];
  if (!c || !c["values"]) {
    throw Error(fmt::format("the isotherm target has no column '{}'", name));
  }
  const std::string unit = c["unit"].as<std::string>("");
  auto values = c["values"].as<std::vector<double>>();
  for (auto& v : values) v = units::to_metal(v, unit);
  return values;
}

}  // namespace

void check_cutoff_between_shells(double cutoff, double v_min, double v_max, int atoms_per_particle,
                                 double margin) {
  // Four particles per cubic cell; shell n of fcc lies at a sqrt(n / 2).
  const double a_min = std::cbrt(4.0 * atoms_per_particle * v_min);
  const double a_max = std::cbrt(4.0 * atoms_per_particle * v_max);
  for (int n = 1; a_min * std::sqrt(n / 2.0) * (1.0 - margin) <= cutoff; ++n) {
    const double lo = a_min * std::sqrt(n / 2.0), hi = a_max * std::sqrt(n / 2.0);
    if (cutoff >= lo * (1.0 - margin) && cutoff <= hi * (1.0 + margin)) {
      throw Error(fmt::format(
          "the cutoff {:g} Å lies on neighbour shell {} of the crystal, which spans {:.3f} to "
          "{:.3f} Å over the targets' volumes (±{:g} % for thermal spread): P(V) would jump "
          "where the shell crosses it. Choose a cutoff between two shells over the whole range",
          cutoff, n, lo, hi, 100.0 * margin));
    }
  }
}

std::vector<bool> default_held_out(size_t n) {
  std::vector<bool> out(n, false);
  for (size_t i = 1; i < n; i += 2) out[i] = true;
  return out;
}

config::StageKindSpec fit_dpd_potential_spec() {
  config::StageKindSpec s;
  s.kind = "fit_dpd_potential";
  s.program = config::kCouplerProgram;
  s.uses = {"dpd_driver"};
  s.doc =
      "Fits a DPD pair style's parameters so that the DPD crystal at a temperature reproduces "
      "MD targets (isotherm, elastic constants, (100) surface energy); dpd_driver judges every "
      "candidate";
  s.material_kinds = {"dpd_mesoparticle"};
  s.params = {
      Param::identifier("material",
                        "The dpd_mesoparticle to fit: its potential is the start and names the "
                        "style; mass and lattice constant are kept")
          .require()
          .material(),
      Param::real("temperature", Dimension::kTemperature, "Temperature of the targets")
          .def(298.0)
          .at_least(0),
      isotherm_param(),
      elastic_param(),
      surface_param(),
      Param::map_of("free",
                    Param::real_list("bounds", Dimension::kNone,
                                     "[lower, upper] in the parameter's metal unit")
                        .length(2, 2),
                    "Free parameters of the style with their bounds; the others stay fixed")
          .require(),
      optimizer_param(),
      judge_param(),
      Param::integer("group_ranks",
                     "dpd_driver ranks per judging group; groups judge state points side by "
                     "side")
          .def(1)
          .above(0),
  };
  s.outputs = {
      {"potential", OutputSpec::Shape::kMap, "", "The fitted potential (a potential file's map)"},
      {"objective", OutputSpec::Shape::kScalar, "1", "Objective at the fitted parameters"},
      {"max_residual_trained", OutputSpec::Shape::kScalar, "1",
       "Largest |relative residual| over the trained targets"},
      {"max_residual_held_out", OutputSpec::Shape::kScalar, "1",
       "Largest |relative residual| over the held-out isotherm points"},
      {"evaluations", OutputSpec::Shape::kScalar, "1", "Candidates judged"},
      {"failed_evaluations", OutputSpec::Shape::kScalar, "1", "Candidates that failed"},
      {"evaluation_log", OutputSpec::Shape::kTable, "",
       "Per candidate: phase, parameters, objective, status, wall time, judged values"},
      {"isotherm", OutputSpec::Shape::kTable, "",
       "Per pressure: target and fitted volume per atom, residual, held out"},
      {"elastic", OutputSpec::Shape::kTable, "", "C11, C12, C44: target and fitted"},
      {"surface_energy_100", OutputSpec::Shape::kScalar, "J/m^2",
       "The fitted crystal's static (100) surface energy (with a surface target)"},
      {"surface_energy_100_target", OutputSpec::Shape::kScalar, "J/m^2",
       "The surface target (with one)"},
  };
  s.check = check_fit;
  return s;
}

FitSettings FitSettings::from_yaml(const YAML::Node& stage, const YAML::Node& materials) {
  FitSettings f;
  f.material = stage["material"].as<std::string>();
  f.atoms_per_particle = materials[f.material]["atoms_per_particle"].as<int>(8);
  f.start_potential = YAML::Clone(materials[f.material]["potential"]);
  f.style = f.start_potential["style"].as<std::string>();
  if (f.start_potential["cutoff"]) f.start_cutoff = f.start_potential["cutoff"].as<double>();
  for (const auto& kv : stage["free"]) {
    const auto b = kv.second.as<std::vector<double>>();
    const std::string name = kv.first.as<std::string>();
    if (!f.start_potential[name]) {
      throw Error(fmt::format("the start potential has no parameter '{}'", name));
    }
    f.free.push_back({name, b[0], b[1], f.start_potential[name].as<double>()});
  }
  f.judge.temperature = stage["temperature"].as<double>();
  if (const YAML::Node iso = stage["isotherm"]) {
    IsothermTarget t;
    t.pressure = column_from_yaml(iso["table"], "pressure");
    t.volume_per_atom = column_from_yaml(iso["table"], "volume_per_atom");
    if (t.pressure.size() != t.volume_per_atom.size() || t.pressure.empty()) {
      throw Error("the isotherm target's pressure and volume_per_atom columns differ in length");
    }
    t.weight = iso["weight"].as<double>();
    t.held_out = default_held_out(t.pressure.size());
    if (iso["held_out"]) {
      t.held_out.assign(t.pressure.size(), false);
      for (const int row : iso["held_out"].as<std::vector<int>>()) {
        if (row >= static_cast<int>(t.pressure.size())) {
          throw Error(fmt::format("isotherm.held_out: row {} is past the table's {} rows", row,
                                  t.pressure.size()));
        }
        t.held_out[static_cast<size_t>(row)] = true;
      }
    }
    f.isotherm = t;
  }
  if (const YAML::Node el = stage["elastic"]) {
    ElasticTarget t;
    if (el["c11"]) t.c11 = el["c11"].as<double>();
    if (el["c12"]) t.c12 = el["c12"].as<double>();
    if (el["c44"]) t.c44 = el["c44"].as<double>();
    t.weight = el["weight"].as<double>();
    f.elastic = t;
  }
  if (const YAML::Node su = stage["surface"]) {
    f.surface = SurfaceTarget{su["energy_100"].as<double>(), su["weight"].as<double>()};
  }
  const YAML::Node o = stage["optimizer"];
  f.optimizer.global = o["global"].as<std::string>();
  f.optimizer.local = o["local"].as<std::string>();
  f.optimizer.global_evaluations = o["global_evaluations"].as<int>();
  f.optimizer.local_evaluations = o["local_evaluations"].as<int>();
  f.optimizer.x_tolerance = o["x_tolerance"].as<double>();
  f.optimizer.f_tolerance = o["f_tolerance"].as<double>();
  f.optimizer.static_prefit = o["static_prefit"].as<bool>();
  f.optimizer.log_scale = o["scale"].as<std::string>() == "log";
  f.judge.sampling = config::CrystalSampling::from_yaml(stage["judge"]);
  if (const YAML::Node seed = stage["judge"]["seed"]) f.judge.seed = seed.as<std::uint64_t>();
  f.group_ranks = stage["group_ranks"].as<int>();
  return f;
}

const config::Param* potential_schema(const std::vector<config::DriverDescription>& drivers) {
  return config::material_field(drivers, "dpd_mesoparticle", "potential");
}

}  // namespace pbms::coupler::fit
