// Every message type survives pack/unpack unchanged; foreign or damaged
// bytes are refused with a message instead of being misread.
#include <gtest/gtest.h>

#include <cmath>

#include "pbms/protocol/messages.hpp"

using namespace pbms::protocol;

namespace {
template <typename T>
T round_trip(const T& m) {
  const auto bytes = pack(m);
  const Message back = unpack(bytes.data(), bytes.size());
  EXPECT_TRUE(std::holds_alternative<T>(back));
  return std::get<T>(back);
}
}  // namespace

TEST(Protocol, Hello) {
  Hello h{"md_driver",        "md", kProtocolVersion, 4, {"md_isotherm", "md_elastic"},
          {"lammps=20220106"}};
  const auto b = round_trip(h);
  EXPECT_EQ(b.program, "md_driver");
  EXPECT_EQ(b.short_name, "md");
  EXPECT_EQ(b.protocol_version, kProtocolVersion);
  EXPECT_EQ(b.ranks, 4);
  EXPECT_EQ(b.capabilities, h.capabilities);
  EXPECT_EQ(b.software, h.software);
}

TEST(Protocol, Welcome) {
  Welcome w{true, "", {{"mpm_driver", 2, 8}, {"dpd_driver", 3, 4}}};
  const auto b = round_trip(w);
  EXPECT_TRUE(b.accepted);
  ASSERT_EQ(b.peers.size(), 2u);
  EXPECT_EQ(b.peers[1].program, "dpd_driver");
  EXPECT_EQ(b.peers[1].app, 3);
  EXPECT_EQ(b.peers[1].ranks, 4);
  Welcome refused{false, "stage 'x' asks for kind 'y'", {}};
  EXPECT_EQ(round_trip(refused).reason, refused.reason);
  EXPECT_FALSE(round_trip(refused).accepted);
}

TEST(Protocol, RunStage) {
  RunStage r{3,
             41,
             "isotherm",
             "md_isotherm",
             "temperature: 298\n",
             "cu: {kind: eam_alloy}",
             "/tmp/run",
             0xfedcba9876543210ULL};
  const auto b = round_trip(r);
  EXPECT_EQ(b.index, 3);
  EXPECT_EQ(b.request, 41);
  EXPECT_EQ(b.name, r.name);
  EXPECT_EQ(b.kind, r.kind);
  EXPECT_EQ(b.params_yaml, r.params_yaml);
  EXPECT_EQ(b.materials_yaml, r.materials_yaml);
  EXPECT_EQ(b.run_dir, r.run_dir);
  EXPECT_EQ(b.seed, r.seed);
}

TEST(Protocol, Progress) {
  Progress p{7, "isotherm", 1234, 37500, 2.468, "P = 5 GPa: production"};
  const auto b = round_trip(p);
  EXPECT_EQ(b.request, 7);
  EXPECT_EQ(b.stage, p.stage);
  EXPECT_EQ(b.step, 1234);
  EXPECT_EQ(b.total_steps, 37500);
  EXPECT_DOUBLE_EQ(b.sim_time_ps, 2.468);
  EXPECT_EQ(b.phase, p.phase);
}

TEST(Protocol, StageDone) {
  StageDone d;
  d.request = 1LL << 40;
  d.stage = "isotherm";
  d.wall_s = 12.5;
  d.results.add_scalar("bulk_modulus", 135.2, "GPa");
  d.results.add_scalar("lattice_parameter", 3.632, "Å", 1e-4);
  d.results.add_column("isotherm", "pressure", "bar", {0.0, 1e4, 5e4});
  d.results.files = {"isotherm/p0.in"};
  d.results.attributes["material"] = "cu";
  const auto b = round_trip(d);
  EXPECT_EQ(b.request, 1LL << 40);
  EXPECT_EQ(b.stage, "isotherm");
  EXPECT_DOUBLE_EQ(b.wall_s, 12.5);
  ASSERT_EQ(b.results.scalars.size(), 2u);
  EXPECT_TRUE(std::isnan(b.results.scalars[0].std_error));
  EXPECT_DOUBLE_EQ(b.results.scalars[1].std_error, 1e-4);
  EXPECT_EQ(b.results.scalars[1].unit, "Å");
  ASSERT_EQ(b.results.columns.size(), 1u);
  EXPECT_EQ(b.results.columns[0].data, (std::vector<double>{0.0, 1e4, 5e4}));
  EXPECT_EQ(b.results.files, d.results.files);
  EXPECT_EQ(b.results.attributes.at("material"), "cu");
}

TEST(Protocol, Fatal) {
  Fatal f{"md_driver", 1, "isotherm", 4200, "LAMMPS stopped: ERROR: Lost atoms"};
  const auto b = round_trip(f);
  EXPECT_EQ(b.program, f.program);
  EXPECT_EQ(b.rank, 1);
  EXPECT_EQ(b.stage, f.stage);
  EXPECT_EQ(b.step, 4200);
  EXPECT_EQ(b.message, f.message);
}

TEST(Protocol, StageFailed) {
  StageFailed f{12, "fit", "dpd_driver", 2, 300, 1.5, "the crystal melted: |dx| > a/2"};
  const auto b = round_trip(f);
  EXPECT_EQ(b.request, 12);
  EXPECT_EQ(b.stage, f.stage);
  EXPECT_EQ(b.program, f.program);
  EXPECT_EQ(b.rank, 2);
  EXPECT_EQ(b.step, 300);
  EXPECT_DOUBLE_EQ(b.wall_s, 1.5);
  EXPECT_EQ(b.reason, f.reason);
}

TEST(Protocol, Regroup) {
  EXPECT_EQ(round_trip(Regroup{3}).group_ranks, 3);
}

TEST(Protocol, Shutdown) {
  EXPECT_EQ(round_trip(Shutdown{"done"}).reason, "done");
}

TEST(Protocol, RefusesOtherVersionsAndDamage) {
  auto bytes = pack(Shutdown{"x"});
  auto other = bytes;
  other[4] = std::byte{9};  // version field
  EXPECT_THROW(unpack(other.data(), other.size()), pbms::Error);
  auto foreign = bytes;
  foreign[0] = std::byte{0};
  EXPECT_THROW(unpack(foreign.data(), foreign.size()), pbms::Error);
  EXPECT_THROW(unpack(bytes.data(), bytes.size() - 1), pbms::Error);
  auto longer = bytes;
  longer.push_back(std::byte{1});
  EXPECT_THROW(unpack(longer.data(), longer.size()), pbms::Error);
}
