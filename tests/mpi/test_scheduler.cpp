// The coupler's scheduler against a real dpd_driver. This program takes the
// coupler's place in an MPMD job:
//   mpirun -np 1 pbms_scheduler_test CONFIG : -np 2 dpd_driver
// and sends variations of the stages in CONFIG (per-request potentials),
// with the driver split into rank groups and whole.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "driver_catalog.hpp"
#include "fit/dpd_judge.hpp"
#include "pbms/config/workflow.hpp"
#include "pbms/io/yaml_file.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/units.hpp"
#include "scheduler.hpp"

namespace {

using pbms::yaml_text;
using pbms::coupler::Answer;
using pbms::coupler::Scheduler;
using pbms::protocol::RequestId;
using pbms::protocol::RunStage;
using pbms::protocol::StageDone;
using pbms::protocol::StageFailed;

const std::string kDpd = "dpd_driver";

Scheduler* g_scheduler = nullptr;
pbms::config::Workflow* g_workflow = nullptr;
const std::vector<pbms::config::DriverDescription>* g_drivers = nullptr;

// Stage `name` of the config with its material's Morse parameters changed.
RunStage request(const std::string& name, const std::map<std::string, double>& potential = {}) {
  const auto& wf = *g_workflow;
  for (size_t i = 0; i < wf.stages.size(); ++i) {
    if (wf.stages[i].name != name) continue;
    YAML::Node materials = YAML::Clone(wf.materials);
    for (const auto& [key, value] : potential) materials["cu_cg"]["potential"][key] = value;
    RunStage rs;
    rs.index = static_cast<int32_t>(i);
    rs.name = name;
    rs.kind = wf.stages[i].kind;
    rs.params_yaml = yaml_text(wf.stages[i].params);
    rs.materials_yaml = yaml_text(materials);
    rs.run_dir = std::filesystem::temp_directory_path() / "pbms_scheduler_test";
    rs.seed = wf.seed;
    return rs;
  }
  throw pbms::Error("no stage " + name);
}

// Every answer to the requests in `ids`, by id; progress is skipped.
std::map<RequestId, Answer> answers(const std::vector<RequestId>& ids) {
  std::map<RequestId, Answer> out;
  while (out.size() < ids.size()) {
    auto a = g_scheduler->next(std::chrono::seconds(120));
    if (!a) throw pbms::Error("no answer within 120 s");
    if (std::holds_alternative<pbms::protocol::Progress>(*a)) continue;
    out.emplace(pbms::coupler::request_of(*a), *a);
  }
  return out;
}

std::vector<double> column(const Answer& a, const std::string& name) {
  const auto& done = std::get<StageDone>(a);
  for (const auto& c : done.results.columns) {
    if (c.name == name) return c.data;
  }
  throw pbms::Error("no column " + name);
}

}  // namespace

// Four requests on two one-rank groups: two run at once, two wait, and each
// answer carries its own request's physics: the static pressure is linear
// in the Morse depth d0.
TEST(Scheduler, GroupsServeRequestsSideBySide) {
  g_scheduler->regroup(kDpd, 1);
  ASSERT_EQ(g_scheduler->groups(kDpd), 2);
  const double d0 = g_workflow->materials["cu_cg"]["potential"]["d0"].as<double>();
  const std::vector<double> scale{1.0, 1.5, 2.0, 3.0};
  std::vector<RequestId> ids;
  for (const double k : scale)
    ids.push_back(g_scheduler->submit(kDpd, request("static", {{"d0", k * d0}})));
  EXPECT_EQ(g_scheduler->running(kDpd), 2u);
  EXPECT_EQ(g_scheduler->unfinished(kDpd), 4u);
  const auto got = answers(ids);
  const auto p1 = column(got.at(ids[0]), "pressure");
  ASSERT_EQ(p1.size(), 3u);
  // Round-off of a pair sum, relative to its largest pressure: near V0 the
  // pressure itself is a small difference of large terms.
  double largest = 0.0;
  for (const double p : p1) largest = std::max(largest, std::abs(p));
  for (size_t k = 0; k < scale.size(); ++k) {
    const auto p = column(got.at(ids[k]), "pressure");
    ASSERT_EQ(p.size(), p1.size());
    for (size_t j = 0; j < p.size(); ++j) {
      EXPECT_NEAR(p[j], scale[k] * p1[j], 1e-12 * scale[k] * largest)
          << "request " << k << ", state " << j;
    }
  }
  EXPECT_EQ(g_scheduler->unfinished(), 0u);
}

// A candidate whose crystal is unstable (Morse r0 far below the neighbour
// distance: the crystal sits past the inflection, dP/dV > 0) fails alone;
// the group that ran it serves the next request.
TEST(Scheduler, FailedRequestLeavesTheDriverInService) {
  g_scheduler->regroup(kDpd, 1);
  RunStage bad = request("static", {{"r0", 2.0}});
  YAML::Node params = YAML::Load(bad.params_yaml);
  params["zero_pressure"] = true;
  bad.params_yaml = yaml_text(params);
  const RequestId failed = g_scheduler->submit(kDpd, bad);
  const auto got = answers({failed});
  const auto* f = std::get_if<StageFailed>(&got.at(failed));
  ASSERT_NE(f, nullptr) << "the unstable crystal gave a result";
  EXPECT_EQ(f->program, kDpd);
  EXPECT_NE(f->reason.find("unstable"), std::string::npos) << f->reason;
  std::vector<RequestId> next;
  for (int k = 0; k < 3; ++k) next.push_back(g_scheduler->submit(kDpd, request("static")));
  for (const auto& [id, a] : answers(next)) EXPECT_TRUE(std::holds_alternative<StageDone>(a));
}

// The same thermal request on a one-rank group and on the whole driver gives
// the same bits: the noise is keyed by the seed, not by the group.
TEST(Scheduler, AnswersDoNotDependOnTheGroups) {
  g_scheduler->regroup(kDpd, 1);
  const std::vector<RequestId> grouped{g_scheduler->submit(kDpd, request("thermal")),
                                       g_scheduler->submit(kDpd, request("thermal"))};
  const auto a = answers(grouped);
  g_scheduler->regroup(kDpd, 2);
  ASSERT_EQ(g_scheduler->groups(kDpd), 1);
  const RequestId whole = g_scheduler->submit(kDpd, request("thermal"));
  const auto b = answers({whole});
  const auto reference = column(b.at(whole), "pressure");
  for (const auto id : grouped) EXPECT_EQ(column(a.at(id), "pressure"), reference);
}

// The fit's judge with elastic targets at 298 K: the lattice constant comes
// from its 0 GPa isotherm request, the four strained states are requests of
// their own, and the constants they combine to are the dpd_elastic stage's
// (zero_pressure: true, the same settings and seed) bit for bit, judged on
// two groups or on one.
TEST(Scheduler, JudgeSplitsTheElasticConstantsOverGroups) {
  using pbms::units::to_metal;
  g_scheduler->regroup(kDpd, 2);
  const RequestId plain = g_scheduler->submit(kDpd, request("elastic"));
  const auto stage = answers({plain});
  const auto& done = std::get<StageDone>(stage.at(plain)).results;
  const auto metal = [&](const std::string& key) {
    for (const auto& r : done.scalars) {
      if (r.key == key) return to_metal(r.value, r.unit);
    }
    throw pbms::Error("no scalar " + key);
  };

  pbms::coupler::fit::FitSettings settings;
  settings.material = "cu_cg";
  settings.judge = {298.0, {0, 50, 100, 1.0e4, 0.01}, std::nullopt};
  settings.isotherm = pbms::coupler::fit::IsothermTarget{{1.0e4, 0.0}, {1.0, 1.0}, {false, false}};
  settings.elastic = pbms::coupler::fit::ElasticTarget{1.0, 1.0, 1.0};
  pbms::config::StageConfig fit{"judge", "fit_dpd_potential", "coupler", {kDpd}, {}, 0};
  pbms::coupler::CouplerStageContext ctx(
      *g_scheduler, fit, g_workflow->materials, *g_drivers,
      std::filesystem::temp_directory_path() / "pbms_scheduler_test", g_workflow->seed, false);
  pbms::coupler::fit::DpdJudge judge(ctx, settings);
  const YAML::Node potential = g_workflow->materials["cu_cg"]["potential"];
  g_scheduler->regroup(kDpd, 1);
  ASSERT_EQ(g_scheduler->groups(kDpd), 2);
  const auto two = judge.judge(potential, 298.0);
  g_scheduler->regroup(kDpd, 2);
  const auto one = judge.judge(potential, 298.0);
  ASSERT_TRUE(two.ok) << two.reason;
  ASSERT_TRUE(one.ok) << one.reason;
  EXPECT_EQ(*two.c11, metal("c11"));
  EXPECT_EQ(*two.c12, metal("c12"));
  EXPECT_EQ(*two.c44, metal("c44"));
  EXPECT_EQ(*two.c11_error, metal("c11_error"));
  EXPECT_EQ(*two.c12_error, metal("c12_error"));
  EXPECT_EQ(*two.c44_error, metal("c44_error"));
  EXPECT_GT(*two.c11_error, 0.0);
  EXPECT_EQ(*one.c11, *two.c11);
  EXPECT_EQ(*one.c12, *two.c12);
  EXPECT_EQ(*one.c44, *two.c44);
  EXPECT_EQ(*one.c44_error, *two.c44_error);
  // The rows come back in the targets' order, the 0 GPa one included.
  ASSERT_EQ(two.volume_per_atom.size(), 2u);
  EXPECT_EQ(one.volume_per_atom, two.volume_per_atom);
  EXPECT_EQ(one.pressure_error, two.pressure_error);
  EXPECT_LT(two.volume_per_atom[0], two.volume_per_atom[1]);
  // The 0 GPa row is the stage's zero-pressure crystal: 8 atoms per mesoparticle.
  const double a = metal("lattice_constant");
  EXPECT_NEAR(two.volume_per_atom[1], a * a * a / 32.0, 1e-12 * two.volume_per_atom[1]);
  EXPECT_EQ(g_scheduler->unfinished(), 0u);
}

TEST(Scheduler, RegroupRefusesWhileBusy) {
  g_scheduler->regroup(kDpd, 1);
  const RequestId id = g_scheduler->submit(kDpd, request("static"));
  EXPECT_THROW(g_scheduler->regroup(kDpd, 2), pbms::Error);
  answers({id});
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (argc != 2) {
    std::cerr << "usage: mpirun -np 1 pbms_scheduler_test CONFIG : -np N dpd_driver\n";
    return 2;
  }
  pbms::mpi::Environment env(argc, argv);
  auto world = pbms::mpi::MpmdWorld::join(pbms::mpi::Role::kCoupler);
  Scheduler scheduler(Scheduler::connect(world), [](const pbms::protocol::Fatal& f) {
    std::cerr << "FATAL from " << f.program << " rank " << f.rank << ": " << f.message << "\n";
    MPI_Abort(MPI_COMM_WORLD, 3);
  });
  const auto drivers = pbms::coupler::discover_drivers(PBMS_BIN_DIR);
  auto loaded = pbms::config::load_workflow(argv[1], drivers);
  for (const auto& e : loaded.errors) std::cerr << e.format() << "\n";
  scheduler.welcome(loaded.workflow.has_value(), "the test's config does not load");
  if (!loaded.workflow) return 1;
  g_scheduler = &scheduler;
  g_workflow = &*loaded.workflow;
  g_drivers = &drivers;
  int rc = 1;
  try {
    rc = RUN_ALL_TESTS();
  } catch (const std::exception& e) {
    std::cerr << "test aborted: " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 3);
  }
  scheduler.shutdown("tests done");
  return rc;
}
