// The speed of a pulse that has no sharp front: the delays with which two
// slabs' displacement histories reach a ladder of levels.
//
// A free rod struck on its end carries a precursor at the dilatational
// speed and the bulk of the pulse near the thin-bar speed; no single
// threshold times both. The delay between the slabs at each level of a
// geometric ladder, averaged, times the pulse's body, and the spread of the
// delays over the ladder shows how much the pulse changes shape between
// the slabs (a non-dispersive pulse gives the same delay at every level).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "first_crossing.hpp"

namespace pbms::analysis {

struct LevelDelays {
  std::vector<double> levels;  // displacement units
  std::vector<double> delays;  // far crossing minus near crossing, time units; NaN if missed
  // The mean of the delays; NaN if either history misses a level.
  [[nodiscard]] double mean() const {
    double sum = 0.0;
    for (const double d : delays) sum += d;
    return delays.empty() ? std::nan("") : sum / static_cast<double>(delays.size());
  }
};

// `count` levels from `lo` to `hi`, equally spaced in their logarithm.
inline LevelDelays level_delays(const std::vector<double>& t, const std::vector<double>& near,
                                const std::vector<double>& far, double lo, double hi,
                                std::size_t count) {
  LevelDelays d;
  for (std::size_t k = 0; k < count; ++k) {
    const double f = count > 1 ? static_cast<double>(k) / static_cast<double>(count - 1) : 0.0;
    const double level = lo * std::pow(hi / lo, f);
    d.levels.push_back(level);
    d.delays.push_back(first_crossing(t, far, level) - first_crossing(t, near, level));
  }
  return d;
}

}  // namespace pbms::analysis
