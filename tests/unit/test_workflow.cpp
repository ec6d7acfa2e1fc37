// Loading workflows against the stage kinds md_driver declares: defaults,
// units, references between stages and the errors users see.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "capabilities.hpp"
#include "eam_material_spec.hpp"
#include "materials/linear_elastic.hpp"
#include "md_elastic.hpp"
#include "md_isotherm.hpp"
#include "md_tension.hpp"
#include "pbms/config/validator.hpp"
#include "pbms/config/workflow.hpp"

using namespace pbms::config;

namespace {

std::vector<DriverDescription> md_only() {
  DriverDescription d;
  d.program = "md_driver";
  d.short_name = "md";
  d.protocol_version = 1;
  d.stage_kinds = {pbms::md::IsothermStage::spec(), pbms::md::ElasticStage::spec(),
                   pbms::md::TensionStage::spec()};
  d.material_kinds = pbms::md::eam_material_kinds();
  return {d};
}

std::string write(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "pbms_unit";
  std::filesystem::create_directories(dir);
  const auto p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

const char* kHeader = R"(run: {name: t, seed: 3}
launch: {md: 2}
materials:
  cu:
    kind: eam_alloy
    potential: /usr/share/lammps/potentials/Cu_mishin1.eam.alloy
    mass: 63.546
    lattice_constant: 3.615
)";

}  // namespace

TEST(Workflow, FillsDefaultsAndConvertsUnits) {
  const auto f = write("ok.yaml", std::string(kHeader) + R"(stages:
  - {name: iso, kind: md_isotherm, material: cu, pressures: [0, 2 GPa, 5 GPa], timestep: 1 fs}
  - {name: wire, kind: md_tension, material: cu, lattice_constant: {from: iso.lattice_parameter}}
)");
  const auto r = load_workflow(f, md_only());
  ASSERT_TRUE(r.errors.empty()) << r.errors[0].format();
  const auto& wf = *r.workflow;
  EXPECT_EQ(wf.run_name, "t");
  EXPECT_EQ(wf.output_dir, "runs");
  EXPECT_EQ(wf.seed, 3u);
  EXPECT_EQ(wf.ranks.at("md_driver"), 2);
  ASSERT_EQ(wf.stages.size(), 2u);
  const auto& iso = wf.stages[0].params;
  EXPECT_DOUBLE_EQ(iso["temperature"].as<double>(), 298.0);
  EXPECT_DOUBLE_EQ(iso["pressures"][2].as<double>(), 5.0e4);
  EXPECT_DOUBLE_EQ(iso["timestep"].as<double>(), 0.001);
  EXPECT_EQ(wf.stages[1].params["lattice_constant"]["from"].as<std::string>(),
            "iso.lattice_parameter");
  EXPECT_EQ(wf.programs(), std::vector<std::string>{"md_driver"});
}

TEST(Workflow, CollectsEveryErrorWithLocation) {
  const auto f = write("bad.yaml", std::string(kHeader) + R"(stages:
  - name: iso
    kind: md_isotherm
    material: cu
    temprature: 300
    cells: [8, 8]
  - name: wire
    kind: md_tension
    material: steel
    lattice_constant: {from: later.lattice_parameter}
  - name: later
    kind: md_isotherm
    material: cu
)");
  const auto r = load_workflow(f, md_only());
  EXPECT_FALSE(r.workflow);
  ASSERT_EQ(r.errors.size(), 4u);
  std::string all;
  for (const auto& e : r.errors) all += e.format() + "\n";
  EXPECT_NE(all.find("bad.yaml:13:5: error: stages[0].temprature: unknown key 'temprature' "
                     "(did you mean 'temperature'?)"),
            std::string::npos)
      << all;
  EXPECT_NE(all.find("stages[0].cells: needs at least 3 entries"), std::string::npos) << all;
  EXPECT_NE(all.find("stages[1].material: material 'steel' is not defined"), std::string::npos)
      << all;
  EXPECT_NE(all.find("stages[1].lattice_constant: stage 'later' runs after this one"),
            std::string::npos)
      << all;
}

TEST(Workflow, RankOverride) {
  const auto f = write(
      "ok2.yaml", std::string(kHeader) + "stages: [{name: e, kind: md_elastic, material: cu}]\n");
  auto r = load_workflow(f, md_only());
  ASSERT_TRUE(r.workflow);
  EXPECT_EQ(apply_rank_override(*r.workflow, md_only(), "md=4"), "");
  EXPECT_EQ(r.workflow->ranks.at("md_driver"), 4);
  EXPECT_NE(apply_rank_override(*r.workflow, md_only(), "md=0"), "");
  EXPECT_NE(apply_rank_override(*r.workflow, md_only(), "dpd=2"), "");
  EXPECT_NE(apply_rank_override(*r.workflow, md_only(), "md"), "");
}

TEST(Workflow, DriverDescriptionRoundTripsThroughYaml) {
  const auto d = md_only()[0];
  const auto back = driver_from_yaml(to_yaml(d));
  ASSERT_EQ(back.stage_kinds.size(), d.stage_kinds.size());
  // The schema rebuilt from YAML validates exactly like the original.
  EXPECT_EQ(YAML::Dump(to_yaml(back)), YAML::Dump(to_yaml(d)));
}

TEST(Capabilities, RefusesUndeclaredKinds) {
  StageConfig s;
  s.name = "impact";
  s.kind = "dpd_run";
  s.program = "md_driver";
  pbms::protocol::Hello h{"md_driver",     "md", pbms::protocol::kProtocolVersion, 2,
                          {"md_isotherm"}, {}};
  const auto problems = pbms::coupler::check_capabilities({s}, {h}, {2});
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("does not declare"), std::string::npos);
  s.kind = "md_isotherm";
  EXPECT_TRUE(pbms::coupler::check_capabilities({s}, {h}, {2}).empty());
  EXPECT_EQ(pbms::coupler::check_capabilities({s}, {h}, {3}).size(), 1u);  // rank mismatch
  s.program = "mpm_driver";
  EXPECT_EQ(pbms::coupler::check_capabilities({s}, {h}, {2}).size(), 1u);  // absent driver
}

namespace {

// md_driver's kinds plus a kind that takes a table and a continuum
// material, as a coupler-side fit or an MPM stage would.
std::vector<DriverDescription> md_and_table_taker() {
  auto drivers = md_only();
  StageKindSpec taker;
  taker.kind = "takes_table";
  taker.program = "md_driver";
  taker.material_kinds = {"linear_elastic"};
  taker.params = {Param::table("targets", "An isotherm"),
                  Param::identifier("material", "A continuum material").material()};
  drivers[0].stage_kinds.push_back(taker);
  drivers[0].material_kinds.push_back(pbms::mpm::LinearElastic::spec());
  return drivers;
}

const char* kElastic = R"(  rod:
    kind: linear_elastic
    density: 8.96
    youngs_modulus: {from: wire.youngs_modulus}
)";

}  // namespace

TEST(Workflow, TableReferencesGoToKeysThatTakeTables) {
  const auto ok = write("table_ok.yaml", std::string(kHeader) + kElastic + R"(stages:
  - {name: iso, kind: md_isotherm, material: cu, pressures: [0, 2 GPa, 5 GPa]}
  - {name: wire, kind: md_tension, material: cu}
  - {name: fit, kind: takes_table, targets: {from: iso.isotherm}, material: rod}
)");
  const auto r = load_workflow(ok, md_and_table_taker());
  ASSERT_TRUE(r.errors.empty()) << r.errors[0].format();

  const auto bad = write("table_bad.yaml", std::string(kHeader) + R"(stages:
  - {name: iso, kind: md_isotherm, material: cu, pressures: [0, 2 GPa, 5 GPa]}
  - {name: a, kind: takes_table, targets: {from: iso.bulk_modulus}}
  - {name: b, kind: takes_table, targets: [1, 2]}
  - {name: c, kind: md_tension, material: cu, lattice_constant: {from: iso.isotherm}}
)");
  auto e = load_workflow(bad, md_and_table_taker());
  ASSERT_EQ(e.errors.size(), 3u);
  std::sort(e.errors.begin(), e.errors.end(),
            [](const auto& x, const auto& y) { return x.line < y.line; });
  EXPECT_EQ(e.errors[0].line, 11);
  EXPECT_NE(e.errors[0].message.find("is a single number; this key takes a table"),
            std::string::npos)
      << e.errors[0].format();
  EXPECT_EQ(e.errors[1].line, 12);
  EXPECT_NE(e.errors[1].message.find("expected a table of an earlier stage"), std::string::npos);
  EXPECT_EQ(e.errors[2].line, 13);
  EXPECT_NE(e.errors[2].message.find("is a table; this key takes a single number"),
            std::string::npos);
}

// A material that takes an earlier stage's result can only be used by the
// stages after that one.
TEST(Workflow, MaterialReferencesFollowTheStageOrder) {
  const auto late = write("material_late.yaml", std::string(kHeader) + kElastic + R"(stages:
  - {name: iso, kind: md_isotherm, material: cu, pressures: [0, 2 GPa, 5 GPa]}
  - {name: fit, kind: takes_table, targets: {from: iso.isotherm}, material: rod}
  - {name: wire, kind: md_tension, material: cu}
)");
  const auto e = load_workflow(late, md_and_table_taker());
  ASSERT_EQ(e.errors.size(), 1u);
  EXPECT_EQ(e.errors[0].line, 12);
  EXPECT_EQ(e.errors[0].key_path, "materials.rod.youngs_modulus");
  EXPECT_NE(e.errors[0].message.find("runs after"), std::string::npos) << e.errors[0].format();
}

namespace {

// Every error of loading `text` as one string, one per line.
std::string errors_of(const std::string& name, const std::string& text) {
  const auto r = load_workflow(write(name, text), md_only());
  std::string all;
  for (const auto& e : r.errors) all += e.format() + "\n";
  return all;
}

}  // namespace

TEST(Workflow, OrdinaryAnchorsAndAliasesAreAccepted) {
  const auto f = write("anchors.yaml", std::string(kHeader) + R"(stages:
  - {name: a, kind: md_elastic, material: cu, cells: &cells [3, 3, 3]}
  - {name: b, kind: md_elastic, material: cu, cells: *cells}
  - &wire {name: c, kind: md_tension, material: cu, cells: [20, 4, 4]}
)");
  const auto r = load_workflow(f, md_only());
  ASSERT_TRUE(r.errors.empty()) << r.errors[0].format();
  EXPECT_EQ(r.workflow->stages[1].params["cells"][2].as<int>(), 3);
}

// YAML merge keys: a stage that is another with a few keys changed.
// The merged stage resolves as if written out, its own keys win, and a
// merge key holding anything but maps is an error at its line.
TEST(Workflow, MergeKeysWriteOutTheMergedMaps) {
  const auto merged = write("merge.yaml", std::string(kHeader) + R"(stages:
  - &base {name: a, kind: md_elastic, material: cu, cells: [3, 3, 3], temperature: 298}
  - <<: *base
    name: b
    cells: [4, 4, 4]
  - {<<: [*base], name: c}
)");
  const auto written = write("written.yaml", std::string(kHeader) + R"(stages:
  - {name: a, kind: md_elastic, material: cu, cells: [3, 3, 3], temperature: 298}
  - {name: b, kind: md_elastic, material: cu, cells: [4, 4, 4], temperature: 298}
  - {name: c, kind: md_elastic, material: cu, cells: [3, 3, 3], temperature: 298}
)");
  const auto m = load_workflow(merged, md_only());
  const auto w = load_workflow(written, md_only());
  ASSERT_TRUE(m.errors.empty()) << m.errors[0].format();
  ASSERT_TRUE(w.errors.empty()) << w.errors[0].format();
  for (std::size_t i = 0; i < 3; ++i) {
    YAML::Emitter a, b;
    a << m.workflow->stages[i].params;
    b << w.workflow->stages[i].params;
    EXPECT_EQ(std::string(a.c_str()), std::string(b.c_str())) << "stage " << i;
  }
  const std::string bad = errors_of(
      "merge_scalar.yaml",
      std::string(kHeader) + "stages:\n  - {<<: 5, name: a, kind: md_elastic, material: cu}\n");
  EXPECT_NE(bad.find("merge_scalar.yaml:10:10: error: <<: a merge key `<<` takes a map"),
            std::string::npos)
      << bad;
}

TEST(Workflow, RefusesAliasesThatCannotBeExpanded) {
  const std::string undefined =
      errors_of("undefined.yaml", std::string(kHeader) +
                                      "stages: [{name: a, kind: md_elastic, material: cu, "
                                      "cells: *nowhere}]\n");
  EXPECT_NE(undefined.find("undefined.yaml:9:59: error: <document>: YAML syntax error: the "
                           "referenced anchor is not defined"),
            std::string::npos)
      << undefined;
  // yaml-cpp would link the alias to the map that holds it: a cycle that
  // every walk of the tree follows until the stack overflows.
  const std::string recursive =
      errors_of("recursive.yaml", std::string(kHeader) +
                                      "stages:\n  - &s {name: a, kind: "
                                      "md_elastic, material: cu, cells: *s}\n");
  EXPECT_NE(recursive.find("recursive.yaml:10:57: error: stages[0].cells: the alias '*s' stands "
                           "inside the node its anchor names (line 10)"),
            std::string::npos)
      << recursive;
  std::string laughs = std::string(kHeader) + "l0: &l0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n";
  for (int i = 1; i <= 7; ++i) {
    laughs += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) laughs += (k ? ", *l" : "*l") + std::to_string(i - 1);
    laughs += "]\n";
  }
  const std::string expanded = errors_of("laughs.yaml", laughs);
  EXPECT_NE(expanded.find("takes the document past 1000000 values"), std::string::npos) << expanded;
}

TEST(Workflow, RefusesSecondDocumentsRepeatedKeysAndNonFiniteNumbers) {
  const std::string two =
      errors_of("two.yaml", std::string(kHeader) +
                                "stages: [{name: a, kind: md_elastic, material: cu}]\n"
                                "---\nrun: {name: other}\n");
  EXPECT_NE(two.find("two.yaml:10:1: error: <document>: a second YAML document starts here"),
            std::string::npos)
      << two;
  const std::string repeated = errors_of(
      "repeated.yaml", std::string(kHeader) +
                           "stages: [{name: a, kind: md_elastic, material: cu, strain: 0.001, "
                           "strain: 0.002}]\n");
  EXPECT_NE(repeated.find("stages[0].strain: the key 'strain' is given twice in this map (first "
                          "on line 9)"),
            std::string::npos)
      << repeated;
  for (const std::string value : {".nan", "nan", ".inf", "-.Inf", "inf K", "infinity"}) {
    const std::string e =
        errors_of("nonfinite.yaml", std::string(kHeader) +
                                        "stages: [{name: a, kind: md_elastic, material: "
                                        "cu, temperature: " +
                                        value + "}]\n");
    EXPECT_NE(
        e.find("stages[0].temperature: expected real [K]: '" + value + "' is not a finite number"),
        std::string::npos)
        << value << ": " << e;
  }
  std::string header = kHeader;
  header.replace(header.find("{md: 2}"), 7, "{md: 3000000000}");
  const std::string big =
      errors_of("int.yaml", header + "stages: [{name: a, kind: md_elastic, material: cu}]\n");
  EXPECT_NE(big.find("launch.md: value 3000000000 is too large: at most 2147483647"),
            std::string::npos)
      << big;
}

TEST(Workflow, NamesUnitsOfTheWrongDimension) {
  const std::string e =
      errors_of("dimension.yaml", std::string(kHeader) +
                                      "stages: [{name: a, kind: md_tension, material: cu, "
                                      "lattice_constant: 2 GPa}]\n");
  EXPECT_NE(e.find("stages[0].lattice_constant: expected real [Å]: 'GPa' in '2 GPa' measures a "
                   "pressure, but this key takes a length: accepted units are Å"),
            std::string::npos)
      << e;
}

TEST(Workflow, LongValuesAndHugeFilesAreRefusedNotCrashed) {
  // A stage name of 60,000 characters is a valid name: checking it used to
  // recurse once per character in std::regex.
  const std::string name(60000, 'n');
  const auto r =
      load_workflow(write("long_name.yaml", std::string(kHeader) + "stages: [{name: " + name +
                                                ", kind: md_elastic, material: cu}]\n"),
                    md_only());
  ASSERT_TRUE(r.errors.empty()) << r.errors[0].format().substr(0, 300);
  EXPECT_EQ(r.workflow->stages[0].name, name);
  // Over 1 MiB: refused at 1:1 before YAML reads it.
  const std::string huge =
      errors_of("huge.yaml", "run: {name: \"" + std::string(3000000, 'a') + "\"}\n");
  EXPECT_NE(huge.find("huge.yaml:1:1: error: <document>: the file is 3000016 bytes; a workflow is "
                      "at most 1048576 bytes"),
            std::string::npos)
      << huge.substr(0, 300);
  // Unknown keys and kinds are shown cut, not in full.
  const std::string kind(50000, 'k');
  const std::string e = errors_of(
      "long_kind.yaml", std::string(kHeader) + "stages: [{name: a, kind: " + kind + "}]\n");
  EXPECT_NE(e.find("unknown stage kind '" + kind.substr(0, 60) + "...'"), std::string::npos)
      << e.substr(0, 300);
  EXPECT_LT(e.size(), 2000u);
}

TEST(Workflow, FileProblemsNameTheCause) {
  EXPECT_EQ(file_problem("/etc/hostname"), "");
  EXPECT_EQ(file_problem("/etc/hostname/x.eam"),
            "cannot exist: '/etc/hostname' is a file, not a directory");
  EXPECT_EQ(file_problem("/etc"), "is a directory, not a file");
  EXPECT_EQ(file_problem("/no/such/file"), "does not exist");
  EXPECT_EQ(directory_problem("/etc/hostname/out/run"),
            "'/etc/hostname' is a file, not a directory");
  EXPECT_EQ(directory_problem("/etc/hostname"), "'/etc/hostname' exists and is not a directory");
  EXPECT_EQ(directory_problem(std::filesystem::temp_directory_path() / "pbms_unit/new/run"), "");
}
