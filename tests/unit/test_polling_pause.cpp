#include <gtest/gtest.h>

#include <chrono>

#include "pbms/mpi/polling_pause.hpp"

using pbms::mpi::PollingPause;
using std::chrono::microseconds;
using std::chrono::milliseconds;

// A short request must not wait out a long sleep: within the first second
// the pause doubles from 50 µs to 1 ms and stays there.
TEST(PollingPause, StaysAtOneMillisecondForTheFirstSecond) {
  microseconds p{0};
  for (int i = 0; i < 40; ++i) p = PollingPause::next(p, milliseconds(i * 20));
  EXPECT_EQ(PollingPause::next(microseconds{0}, milliseconds(0)), microseconds(50));
  EXPECT_EQ(PollingPause::next(microseconds(50), milliseconds(0)), microseconds(100));
  EXPECT_EQ(p, microseconds(1000));
}

// Long work on the other side: the pause grows to 20 ms, no further.
TEST(PollingPause, GrowsToTwentyMillisecondsOnALongWait) {
  microseconds p{1000};
  for (int i = 0; i < 10; ++i) p = PollingPause::next(p, std::chrono::seconds(2));
  EXPECT_EQ(p, microseconds(20000));
}

// Sleeping a pause really sleeps at least the ladder's pauses (how long
// beyond them is the scheduler's business, not a test's).
TEST(PollingPause, SleepsItsPause) {
  PollingPause pause;
  const auto t0 = PollingPause::Clock::now();
  for (int i = 0; i < 8; ++i) pause.sleep();  // 50 µs .. 1 ms
  EXPECT_GE(PollingPause::Clock::now() - t0, microseconds(50 + 100 + 200 + 400 + 800 + 3 * 1000));
}
