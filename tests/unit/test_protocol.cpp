// Every message type survives pack/unpack unchanged; foreign or damaged
// bytes are refused with a message instead of being misread.
#include <gtest/gtest.h>

#include <cmath>

#include "pbms/coupling/body_handover.hpp"
#include "pbms/protocol/messages.hpp"
#include "pbms/protocol/wire.hpp"

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
             0xfedcba9876543210ULL,
             "every_steps: 100\n",
             "/tmp/run/md/checkpoints/step_000000000100.h5"};
  const auto b = round_trip(r);
  EXPECT_EQ(b.index, 3);
  EXPECT_EQ(b.request, 41);
  EXPECT_EQ(b.name, r.name);
  EXPECT_EQ(b.kind, r.kind);
  EXPECT_EQ(b.params_yaml, r.params_yaml);
  EXPECT_EQ(b.materials_yaml, r.materials_yaml);
  EXPECT_EQ(b.run_dir, r.run_dir);
  EXPECT_EQ(b.seed, r.seed);
  EXPECT_EQ(b.checkpoint_yaml, r.checkpoint_yaml);
  EXPECT_EQ(b.resume_from, r.resume_from);
}

TEST(Protocol, Progress) {
  Progress p{7, "isotherm", 1234, 37500, 2.468, "P = 5 GPa: production", "iso/c.h5"};
  const auto b = round_trip(p);
  EXPECT_EQ(b.request, 7);
  EXPECT_EQ(b.stage, p.stage);
  EXPECT_EQ(b.step, 1234);
  EXPECT_EQ(b.total_steps, 37500);
  EXPECT_DOUBLE_EQ(b.sim_time_ps, 2.468);
  EXPECT_EQ(b.phase, p.phase);
  EXPECT_EQ(b.checkpoint, p.checkpoint);
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

// The concurrent stage's hand-over travels as a typed struct: every field,
// fixed-size arrays included, comes back bit for bit, and a cut message is
// refused rather than misread.
TEST(Protocol, BodyHandoverRoundTrips) {
  pbms::coupling::BodyHandover h;
  h.groups = {"flyer", "target", "grip_left"};
  h.band_lo = {3, -1, 0};
  h.band_hi = {9, 12, 40};
  h.reach = 11.0 + 1.0 / 3.0;
  h.skin = 1.0;
  h.points.push_back({7, {1.5, -2.25, 1e-300}, {0.1, 0.2, -0.3}, 508.37, 0b101u});
  h.points.push_back({123456789012LL, {0.0, 7.23, 14.46}, {0.0, 0.0, 0.0}, 508.37, 0u});
  pbms::protocol::Encoder e;
  e.put(h);
  const auto bytes = e.take();
  pbms::protocol::Decoder d(bytes.data(), bytes.size());
  pbms::coupling::BodyHandover back;
  d.get(back);
  EXPECT_TRUE(d.at_end());
  EXPECT_EQ(back.groups, h.groups);
  EXPECT_EQ(back.band_lo, h.band_lo);
  EXPECT_EQ(back.band_hi, h.band_hi);
  EXPECT_EQ(back.band().count(), h.band().count());
  EXPECT_EQ(back.reach, h.reach);
  EXPECT_EQ(back.skin, h.skin);
  ASSERT_EQ(back.points.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.points[i].id, h.points[i].id);
    EXPECT_EQ(back.points[i].x, h.points[i].x);
    EXPECT_EQ(back.points[i].v, h.points[i].v);
    EXPECT_EQ(back.points[i].mass, h.points[i].mass);
    EXPECT_EQ(back.points[i].groups, h.points[i].groups);
  }
  pbms::protocol::Decoder cut(bytes.data(), bytes.size() - 5);
  pbms::coupling::BodyHandover broken;
  EXPECT_THROW(cut.get(broken), pbms::Error);
}
