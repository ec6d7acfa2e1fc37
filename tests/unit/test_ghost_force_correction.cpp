// The ghost-force correction's dead load: the mean of the reactions over
// the averaged steps, each part's net taken out, subtracted per point by id
// whatever the points' order, with nothing on points that never had a
// partner.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "pbms/coupling/ghost_force_correction.hpp"

namespace {

using pbms::coupling::GhostForceCorrection;
using pbms::coupling::Vec3;

TEST(GhostForceCorrection, OneStepMakesTheReferenceForceFree) {
  GhostForceCorrection g(MPI_COMM_SELF, 1);
  const std::vector<std::int64_t> id{7, 3, 9};
  const std::vector<int> part{0, 0, 0};
  std::vector<Vec3> f{{1.5, 0.0, -0.25}, {0.0, 0.0, 0.0}, {-1.5, 0.0, 0.25}};
  g.correct(id, part, f);
  for (const auto& v : f) EXPECT_EQ(v, (Vec3{0.0, 0.0, 0.0}));
  EXPECT_EQ(g.points(), 2u);  // point 3 took nothing
  EXPECT_DOUBLE_EQ(g.largest(), std::hypot(1.5, 0.25));
  EXPECT_DOUBLE_EQ(g.net_removed(), 0.0);
  // Later steps, the points reordered: each loses its own dead load.
  const std::vector<std::int64_t> later{9, 3, 7};
  std::vector<Vec3> h{{-1.0, 2.5, 0.25}, {0.5, 0.0, 0.0}, {2.0, 0.0, -0.25}};
  g.correct(later, part, h);
  EXPECT_EQ(h[0], (Vec3{0.5, 2.5, 0.0}));
  EXPECT_EQ(h[1], (Vec3{0.5, 0.0, 0.0}));
  EXPECT_EQ(h[2], (Vec3{0.5, 0.0, 0.0}));
}

TEST(GhostForceCorrection, TheDeadLoadIsTheMeanOverTheAveragedSteps) {
  GhostForceCorrection g(MPI_COMM_SELF, 4);
  const std::vector<std::int64_t> id{1, 2};
  const std::vector<int> part{0, 0};
  const double r[4] = {1.0, 3.0, 2.0, 6.0};  // mean 3
  double running_sum = 0.0;
  for (int k = 0; k < 4; ++k) {
    std::vector<Vec3> f{{r[k], 0.0, 0.0}, {-r[k], 0.0, 0.0}};
    g.correct(id, part, f);
    running_sum += r[k];
    // While averaging, a point feels its reaction less the running mean.
    EXPECT_DOUBLE_EQ(f[0][0], r[k] - running_sum / (k + 1));
  }
  EXPECT_TRUE(g.measured());
  EXPECT_DOUBLE_EQ(g.largest(), 3.0);
  std::vector<Vec3> f{{3.0, 1.0, 0.0}, {-3.0, 0.0, 0.0}};
  g.correct(id, part, f);
  EXPECT_EQ(f[0], (Vec3{0.0, 1.0, 0.0}));
  EXPECT_EQ(f[1], (Vec3{0.0, 0.0, 0.0}));
}

// A part's mean net force is taken out of its points' dead loads alike,
// part by part: the correction pushes no part as a whole.
TEST(GhostForceCorrection, EachPartsDeadLoadsSumToZero) {
  GhostForceCorrection g(MPI_COMM_SELF, 1);
  const std::vector<std::int64_t> id{1, 2, 3};
  const std::vector<int> part{0, 0, 5};
  std::vector<Vec3> f{{2.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  g.correct(id, part, f);
  // The first step sees its reactions less the running mean (all of them).
  for (const auto& v : f) EXPECT_EQ(v, (Vec3{0.0, 0.0, 0.0}));
  EXPECT_DOUBLE_EQ(g.net_removed(), 3.0);
  std::vector<Vec3> zero(3, Vec3{0.0, 0.0, 0.0});
  g.correct(id, part, zero);
  EXPECT_EQ(zero[0], (Vec3{-0.5, 0.0, 0.0}));
  EXPECT_EQ(zero[1], (Vec3{0.5, 0.0, 0.0}));
  EXPECT_EQ(zero[2], (Vec3{0.0, 0.0, 0.0}));
}

TEST(GhostForceCorrection, ResumesFromItsCheckpointMidAverage) {
  GhostForceCorrection a(MPI_COMM_SELF, 3), b(MPI_COMM_SELF, 3);
  const std::vector<std::int64_t> id{4, 5};
  const std::vector<int> part{1, 1};
  std::vector<Vec3> f{{1.0, 0.0, 0.0}, {0.0, -2.0, 0.0}};
  auto f2 = f;
  a.correct(id, part, f);
  b.correct(id, part, f2);
  pbms::CheckpointArchive archive;
  a.save(archive);
  const auto file = std::filesystem::temp_directory_path() / "pbms_ghost_forces_test.h5";
  archive.write(file, "ghost forces");
  GhostForceCorrection resumed(MPI_COMM_SELF, 3);
  resumed.load(pbms::CheckpointArchive::read(file, "ghost forces", MPI_COMM_SELF));
  std::filesystem::remove(file);
  for (int k = 0; k < 3; ++k) {
    std::vector<Vec3> x{{2.0 + k, 0.0, 0.0}, {0.0, 1.0, 0.0}};
    auto y = x;
    resumed.correct(id, part, x);
    b.correct(id, part, y);
    EXPECT_EQ(x, y);
  }
  EXPECT_EQ(resumed.net_removed(), b.net_removed());
}

// A later stage applies what an earlier one measured and wrote.
TEST(GhostForceCorrection, ALaterStageReadsTheDeadLoads) {
  GhostForceCorrection g(MPI_COMM_SELF, 1);
  const std::vector<std::int64_t> id{11, 12};
  const std::vector<int> part{0, 0};
  std::vector<Vec3> f{{0.5, -1.0, 0.0}, {-0.5, 1.0, 0.0}};
  g.correct(id, part, f);
  const auto file = std::filesystem::temp_directory_path() / "pbms_ghost_forces_read_test.h5";
  g.write(file);
  GhostForceCorrection later = GhostForceCorrection::read(MPI_COMM_SELF, file);
  std::filesystem::remove(file);
  EXPECT_TRUE(later.measured());
  EXPECT_EQ(later.points(), 2u);
  std::vector<Vec3> h{{0.5, -1.0, 0.0}, {-0.5, 1.0, 0.0}};
  later.correct(id, part, h);
  for (const auto& v : h) EXPECT_EQ(v, (Vec3{0.0, 0.0, 0.0}));
}

}  // namespace
