// A prescribed velocity (a grip's, a piston's) reached linearly over a
// ramp time. Grips that start at full speed send a stress step of about
// rho c v through a rod, and a gauge read while that wave runs sees a
// dynamic modulus; ramped over a wave transit or more the rod is loaded
// nearly quasi-statically from the start. Both drivers take a step's
// velocity at the step's midpoint, so that a DPD grip and an MPM grip with
// the same ramp move alike (and by ramp_displacement exactly: the midpoint
// rule is exact for a linear ramp).
#pragma once

#include <algorithm>
#include <cstdint>

namespace pbms {

// The fraction of the full velocity during step `step` (from (step - 1) dt
// to step dt); 1 without a ramp.
[[nodiscard]] inline double ramp_fraction(std::int64_t step, double dt, double ramp_time) {
  if (!(ramp_time > 0.0)) return 1.0;
  return std::min(1.0, (static_cast<double>(step) - 0.5) * dt / ramp_time);
}

// How far a group moving at unit full speed has gone by time t.
[[nodiscard]] inline double ramp_displacement(double t, double ramp_time) {
  if (!(ramp_time > 0.0)) return t;
  if (t < ramp_time) return 0.5 * t * t / ramp_time;
  return t - 0.5 * ramp_time;
}

}  // namespace pbms
