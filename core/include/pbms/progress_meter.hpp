// Turns a stream of (step, total, simulated time) reports into progress
// lines with a rate and an ETA. Decides when a line is worth printing: on a
// terminal a refreshed line a few times a second, in a log about every 10 %.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace pbms {

class ProgressMeter {
 public:
  // `item` names what is counted: "step", or "evaluation" for a fit.
  ProgressMeter(std::string label, bool terminal, std::string item = "step")
      : label_(std::move(label)), terminal_(terminal), item_(std::move(item)) {}

  // `now_s` is wall time in seconds from any fixed origin; a negative
  // `sim_time_ps` leaves simulated time out of the line. Returns the line
  // to print, or nothing if it is not yet due.
  std::optional<std::string> update(int64_t step, int64_t total, double sim_time_ps,
                                    const std::string& phase, double now_s);
  // The line as it would be printed now (used for the final line).
  [[nodiscard]] std::string format(int64_t step, int64_t total, double sim_time_ps,
                                   const std::string& phase, double now_s) const;

 private:
  std::string label_;
  bool terminal_;
  std::string item_;
  static constexpr double kShortest = 0.5;  // s: no rate over a shorter span
  double start_s_ = -1.0;
  int64_t start_step_ = 0;
  double last_print_s_ = -1.0;
  int last_decile_ = -1;
};

// "1h02m", "3m05s", "42s"
std::string format_duration(double seconds);

}  // namespace pbms
