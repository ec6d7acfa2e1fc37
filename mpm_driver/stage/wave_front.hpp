// The seed's Appendix-2 bar as an analysis: a bar fixed at one end, with a
// step traction applied at the other at t = 0. The exact stress is a sum of
// step waves reflected at both ends (d'Alembert): reflections at the fixed
// end keep the sign of the stress jump, reflections at the loaded end (where
// the stress is held at the traction) invert it.
#pragma once

#include <vector>

namespace pbms::mpm {

struct StepLoadedBar {
  double loaded_end = 0.0;  // coordinate of the loaded end
  double fixed_end = 0.0;   // coordinate of the fixed end
  double traction = 0.0;    // stress applied at the loaded end
  double wave_speed = 0.0;  // sqrt(M / rho)

  [[nodiscard]] double length() const;
  // Exact axial stress at coordinate x and time t >= 0.
  [[nodiscard]] double exact_stress(double x, double t) const;
  // Time the first front needs to reach the fixed end.
  [[nodiscard]] double transit_time() const { return length() / wave_speed; }
};

// Where the first front is: of the points whose stress has reached half the
// traction, the one farthest from the loaded end; its distance from there.
[[nodiscard]] double front_distance(const StepLoadedBar& bar, const std::vector<double>& x,
                                    const std::vector<double>& stress);

// sqrt(mean((stress - exact)^2)) over the points.
[[nodiscard]] double rms_from_exact(const StepLoadedBar& bar, double t,
                                    const std::vector<double>& x,
                                    const std::vector<double>& stress);

// How much the stress profile oscillates beyond the exact one: the total
// variation sum |s_{k+1} - s_k| of the stresses taken in order of x, minus
// the exact profile's (its jumps). Cell-crossing noise shows up here while
// the front's dispersion, which no grid of this spacing avoids, does not.
[[nodiscard]] double excess_variation(const StepLoadedBar& bar, double t,
                                      const std::vector<double>& x,
                                      const std::vector<double>& stress);

// Volume-weighted mean stress of the points between 0.1 L from the loaded
// end and 0.1 L behind the exact front, at a time before the first
// reflection. The window stays clear of the loaded end and of the front's
// dispersive ringing; taken late (0.8 L/c) it spans several wavelengths of
// the ringing that trails the front, which then averages out.
[[nodiscard]] double plateau_stress(const StepLoadedBar& bar, double t,
                                    const std::vector<double>& x, const std::vector<double>& stress,
                                    const std::vector<double>& volume);

}  // namespace pbms::mpm
