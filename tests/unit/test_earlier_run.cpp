#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "earlier_run.hpp"

namespace pbms::coupler {
namespace {

// --resume compares the config with the one the earlier run resolved, and
// names the first key that differs, whichever side lacks it.
TEST(EarlierRunConfig, NamesAKeyTheNewConfigDropped) {
  const YAML::Node then = YAML::Load("stages: [{name: a, wave: {baseline: {dpd: x, mpm: y}}}]");
  const YAML::Node now = YAML::Load("stages: [{name: a, wave: {baseline: {dpd: x}}}]");
  EXPECT_EQ(first_difference(then, now),
            "stages[0].wave.baseline.mpm: 'y' in the earlier run, (not given) now");
}

TEST(EarlierRunConfig, NamesAKeyTheNewConfigAdded) {
  const YAML::Node then = YAML::Load("stages: [{name: a}]");
  const YAML::Node now = YAML::Load("stages: [{name: a, steps: 5}]");
  EXPECT_EQ(first_difference(then, now),
            "stages[0].steps: (not given) in the earlier run, '5' now");
}

TEST(EarlierRunConfig, WhereTheRunLiesAndItsRanksMayChange) {
  const YAML::Node then = YAML::Load("run: {name: a, output: x}\nlaunch: {dpd: 1}\nsteps: 3");
  const YAML::Node now = YAML::Load("run: {name: b, output: y}\nlaunch: {dpd: 4}\nsteps: 3");
  EXPECT_EQ(first_difference(then, now), "");
}

}  // namespace
}  // namespace pbms::coupler
