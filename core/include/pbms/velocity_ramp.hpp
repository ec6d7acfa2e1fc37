// A prescribed velocity (a grip's, a piston's) reached linearly over a
// ramp time. Grips that start at full speed send a stress step of about
// rho c v through a rod, and a gauge read while that wave runs sees a
// dynamic modulus; ramped over a wave transit or more the rod is loaded
// nearly quasi-statically from the start. Both drivers take a step's
// velocity as its mean over the step, so that a DPD grip and an MPM grip
// with the same ramp move alike, by ramp_displacement exactly.
#pragma once

#include <algorithm>
#include <cstdint>

namespace pbms {

// How far a group moving at unit full speed has gone by time t.
[[nodiscard]] inline double ramp_displacement(double t, double ramp_time) {
  if (!(ramp_time > 0.0)) return t;
  if (t < ramp_time) return 0.5 * t * t / ramp_time;
  return t - 0.5 * ramp_time;
}

// The fraction of the full velocity during step `step` (from (step - 1) dt
// to step dt): the step's mean, so that the group has gone exactly
// ramp_displacement by the end of every step, also the step in which the
// ramp ends; 1 without a ramp.
[[nodiscard]] inline double ramp_fraction(std::int64_t step, double dt, double ramp_time) {
  const double t0 = static_cast<double>(step - 1) * dt;
  if (!(ramp_time > 0.0) || t0 >= ramp_time) return 1.0;
  const double t1 = t0 + dt;
  return (ramp_displacement(t1, ramp_time) - ramp_displacement(std::max(t0, 0.0), ramp_time)) / dt;
}

}  // namespace pbms
