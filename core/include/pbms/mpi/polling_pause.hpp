// How an idle process waits for a message without spinning a core.
#pragma once

#include <chrono>

namespace pbms::mpi {

// MPI's blocking calls spin while they wait, and PBMS runs its programs
// oversubscribed, so idle processes poll with a sleep between tries. The
// sleep doubles from 50 µs. For the first second of a wait it stays at or
// below 1 ms: a request that takes milliseconds (a fit's static crystal, a
// coupling step) then costs a millisecond of latency, not the 20 ms a longer
// sleep adds on each side of every round trip (2026-12-06: 0.4 s of a fit
// candidate's 0.41 s was two programs asleep in turn). After a second, the
// wait is long work on the other side and the sleep may grow to 20 ms.
class PollingPause {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::microseconds kFirst{50};
  static constexpr std::chrono::microseconds kShortWaitCap{1000};
  static constexpr std::chrono::microseconds kLongWaitCap{20000};
  static constexpr std::chrono::seconds kShortWait{1};

  // The sleep after `previous`, once the wait has lasted `waited`.
  static std::chrono::microseconds next(std::chrono::microseconds previous, Clock::duration waited);

  // Sleeps the next pause of this wait.
  void sleep();

 private:
  Clock::time_point start_ = Clock::now();
  std::chrono::microseconds pause_{0};
};

}  // namespace pbms::mpi
