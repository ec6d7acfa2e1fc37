#include "pbms/mpi/polling_pause.hpp"

#include <algorithm>
#include <thread>

namespace pbms::mpi {

std::chrono::microseconds PollingPause::next(std::chrono::microseconds previous,
                                             Clock::duration waited) {
  const auto cap = waited < kShortWait ? kShortWaitCap : kLongWaitCap;
  if (previous.count() <= 0) return kFirst;
  return std::min(previous * 2, cap);
}

void PollingPause::sleep() {
  pause_ = next(pause_, Clock::now() - start_);
  std::this_thread::sleep_for(pause_);
}

}  // namespace pbms::mpi
