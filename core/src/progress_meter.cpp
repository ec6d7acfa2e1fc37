#include "pbms/progress_meter.hpp"

#include <cmath>

#include <fmt/format.h>

namespace pbms {

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  const auto t = static_cast<long long>(std::llround(s));
  if (t >= 3600) return fmt::format("{}h{:02}m", t / 3600, (t % 3600) / 60);
  if (t >= 60) return fmt::format("{}m{:02}s", t / 60, t % 60);
  return fmt::format("{}s", t);
}

std::string ProgressMeter::format(int64_t step, int64_t total, double sim_time_ps,
                                  const std::string& phase, double now_s) const {
  // The rate counts from the first report on: the steps before it (a
  // stage's first report may come late) took time the meter never saw,
  // and half a second is too short to measure a rate over.
  const double elapsed = start_s_ >= 0 ? now_s - start_s_ : 0.0;
  const double rate =
      elapsed >= kShortest ? static_cast<double>(step - start_step_) / elapsed : 0.0;
  const double eta = rate > 0 ? static_cast<double>(total - step) / rate : NAN;
  const double pct = total > 0 ? 100.0 * static_cast<double>(step) / static_cast<double>(total) : 0;
  // The first report has no elapsed time to measure a rate against.
  const std::string speed = rate >= 100 ? fmt::format("{:.0f} {}s/s", rate, item_)
                            : rate > 0  ? fmt::format("{:.3g} {}s/s", rate, item_)
                                        : fmt::format("- {}s/s", item_);
  // A negative simulated time: the work has none (a fit's evaluations).
  const std::string sim = sim_time_ps >= 0 ? fmt::format(" | {:.2f} ps", sim_time_ps) : "";
  std::string line = fmt::format("[{}] {} {}/{} ({:3.0f}%){} | {} | ETA {}", label_, item_, step,
                                 total, pct, sim, speed, format_duration(eta));
  if (!phase.empty()) line += " | " + phase;
  return line;
}

std::optional<std::string> ProgressMeter::update(int64_t step, int64_t total, double sim_time_ps,
                                                 const std::string& phase, double now_s) {
  if (start_s_ < 0) {
    start_s_ = now_s;
    start_step_ = step;
  }
  bool due = false;
  if (terminal_) {
    due = last_print_s_ < 0 || now_s - last_print_s_ >= 0.2 || step >= total;
  } else {
    const int decile = total > 0 ? static_cast<int>(10 * step / total) : 0;
    due = decile > last_decile_;
    if (due) last_decile_ = decile;
  }
  if (!due) return std::nullopt;
  last_print_s_ = now_s;
  return format(step, total, sim_time_ps, phase, now_s);
}

}  // namespace pbms
