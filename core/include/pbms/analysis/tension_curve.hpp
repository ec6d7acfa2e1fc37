// The analysis of a sampled stress-strain curve of a tension test, shared by
// dpd_run and mpm_run so that a DPD rod and the MPM rod calibrated from it
// are judged by the same rules: Young's modulus from a linear fit over the
// elastic part, and the yield point at the first load drop.
#pragma once

#include <cstddef>
#include <vector>

namespace pbms::analysis {

// When a load drop counts. A thermal (DPD) curve wiggles by a fraction of a
// GPa from sample to sample, and a pulled rod rings in its first
// picoseconds, so neither a raw maximum nor the first decrease will do:
//  1. the stress is smoothed by a centred running mean over `smoothing`
//     of strain;
//  2. its noise is the scatter of the raw samples about that mean (a
//     median absolute deviation, so that the drop itself does not inflate
//     it), scaled to a standard deviation;
//  3. walking up in strain, the running maximum of the smoothed stress is
//     a candidate peak; the first candidate from which the smoothed stress
//     later falls by more than max(drop_fraction * peak, noise_multiple *
//     noise) before exceeding it again is the yield point, provided the
//     peak is at least min_peak_fraction of the largest smoothed stress
//     (the ringing of the first picoseconds happens at low stress).
struct YieldRule {
  double smoothing = 0.005;
  double drop_fraction = 0.02;
  double noise_multiple = 3.0;
  double min_peak_fraction = 0.5;
};

struct YieldPoint {
  bool found = false;
  std::size_t index = 0;  // the sample of the peak
  double stress = 0.0;    // smoothed stress at the peak
  double strain = 0.0;
  double noise = 0.0;  // standard deviation of a raw sample about the smoothed curve
};

// Centred running mean of y over samples whose x lies within ±window/2.
std::vector<double> running_mean(const std::vector<double>& x, const std::vector<double>& y,
                                 double window);

// The first load drop of stress(strain) under `rule`; found = false if the
// curve never drops that far (still rising, or a plateau).
YieldPoint first_load_drop(const std::vector<double>& strain, const std::vector<double>& stress,
                           const YieldRule& rule);

}  // namespace pbms::analysis
