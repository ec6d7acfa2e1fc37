// Whether a baseline's histories can be subtracted from a run's sample by
// sample: an impact analysis's baseline (a run of the same body, start and
// noise, not struck) must have been sampled every step of the same length
// over at least as many steps.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace pbms::analysis {

// `time` holds the baseline's sample times (ps); the run takes `steps`
// steps of `dt` ps and samples at each, step 0 included.
inline bool baseline_covers(const std::vector<double>& time, std::int64_t steps, double dt) {
  if (time.size() < static_cast<std::size_t>(steps) + 1) return false;
  return steps == 0 || std::abs(time[1] - time[0] - dt) <= 1e-9 * dt;
}

}  // namespace pbms::analysis
