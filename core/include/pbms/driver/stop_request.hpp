// A wall-time limit's warning: SIGTERM, or SIGUSR1 (what `./pbms run`
// forwards to the job through mpirun, and what Slurm's --signal sends).
// While a stage that writes checkpoints runs (a StopWindow is open), the
// signal asks it to write one at the next step boundary and stop; at any
// other time the process ends as it would without a handler.
#pragma once

#include <string_view>

namespace pbms {

// How the failure of a stage stopped on request begins: the coupler tells
// it from a real failure by this.
inline constexpr std::string_view kStoppedBySignal = "stopped by a signal";

// Installs the handler for SIGTERM and SIGUSR1 (once per process).
void install_stop_handlers();
// Whether this process has been asked to stop.
[[nodiscard]] bool stop_requested();

// Open while a stage can honour a stop request (scoped).
class StopWindow {
 public:
  StopWindow();
  ~StopWindow();
  StopWindow(const StopWindow&) = delete;
  StopWindow& operator=(const StopWindow&) = delete;
};

}  // namespace pbms
