// Loading workflows against the stage kinds md_driver declares: defaults,
// units, references between stages and the errors users see.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "capabilities.hpp"
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
  pbms::protocol::Hello h{"md_driver", "md", 1, 2, {"md_isotherm"}, {}};
  const auto problems = pbms::coupler::check_capabilities({s}, {h}, {2});
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("does not declare"), std::string::npos);
  s.kind = "md_isotherm";
  EXPECT_TRUE(pbms::coupler::check_capabilities({s}, {h}, {2}).empty());
  EXPECT_EQ(pbms::coupler::check_capabilities({s}, {h}, {3}).size(), 1u);  // rank mismatch
  s.program = "mpm_driver";
  EXPECT_EQ(pbms::coupler::check_capabilities({s}, {h}, {2}).size(), 1u);  // absent driver
}
