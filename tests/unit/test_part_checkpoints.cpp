#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "part_checkpoints.hpp"

using pbms::coupler::PartCheckpoints;

// A concurrent stage's checkpoint counts once both parts wrote their files,
// whichever reports first, and steps complete independently.
TEST(PartCheckpoints, CompleteOnlyOnceEveryPartReported) {
  PartCheckpoints c(2);
  EXPECT_FALSE(c.add(1, 100, "s/step_100.mpm.h5"));
  EXPECT_FALSE(c.add(0, 150, "s/step_150.h5"));
  const auto first = c.add(0, 100, "s/step_100.h5");
  ASSERT_TRUE(first);
  EXPECT_EQ(*first, (std::vector<std::string>{"s/step_100.h5", "s/step_100.mpm.h5"}));
  const auto second = c.add(1, 150, "s/step_150.mpm.h5");
  ASSERT_TRUE(second);
  EXPECT_EQ(second->front(), "s/step_150.h5");
  // A step already complete starts afresh.
  EXPECT_FALSE(c.add(1, 100, "again"));
}

TEST(PartCheckpoints, OnePartIsCompleteAtOnce) {
  PartCheckpoints c(1);
  const auto files = c.add(0, 10, "s/step_10.h5");
  ASSERT_TRUE(files);
  EXPECT_EQ(files->size(), 1u);
}
