// The gauge of a tension test: a section of the rod between two planes of
// the starting configuration, away from the grips, on which the Cauchy
// stress and the local strain are read. The rod measure (the stress
// integral over the whole rod, over A0 L) carries the grips and the
// shrinking section in its numbers, so a material calibrated from it loses
// them a second time (docs/hierarchy.md); the gauge reads the material.
//
// Both programs read the gauge the same way, on material sets fixed at the
// start (particles or points by their starting axial coordinate X):
//  - strain: the distance between the centroids of the gauge's two halves
//    over its starting value, minus one. Every particle of the gauge takes
//    part, so thermal noise averages out, and a uniform stretch of the
//    gauge gives exactly its strain;
//  - stress: the force that the material beyond a plane of the gauge exerts
//    across it, averaged over all planes of the gauge, over the current
//    cross-section (dpd_run: the rod's nominal section at the start,
//    following the gauge's lateral extents in proportion), or the volume mean of the Cauchy stress of
//    the gauge's points (mpm_run); the two agree for a uniform section.
// The force across a material plane is the sum of the forces on everything
// behind it, because pair forces between two particles behind it cancel.
// Averaged over the planes, each particle's force enters with the weight
// weight(X): 1 behind the gauge, falling linearly to 0 across it.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/param.hpp"

namespace pbms::analysis {

struct GaugeSection {
  double lo = 0.0, hi = 0.0;  // starting axial coordinates of its ends, Å
  // The modulus is fitted up to the first sample reaching this fraction of
  // the largest smoothed stress: the small-strain slope, the same for a
  // nonlinear DPD curve and the linear elastic part of a J2 rod.
  double fit_stress_fraction = 0.5;

  // The `gauge` map inside a stage's tension map.
  static config::Param param();
  static GaugeSection from_yaml(const YAML::Node& gauge);

  // 1 for X ≤ lo, 0 for X ≥ hi, linear between.
  [[nodiscard]] double weight(double x0) const;
  // 0: the gauge's lower half; 1: its upper half; -1: outside the gauge.
  [[nodiscard]] int half(double x0) const;
};

// One sample's sums over a rank's particles or points, to be reduced over
// the ranks of a program: `sums` by addition, `minima` by minimum.
struct GaugeSums {
  // weighted axial force (eV/Å), Σ σ_aa V (bar Å^3), Σ V (Å^3), then per
  // half: count and Σ of the axial coordinate.
  std::array<double, 7> sums{};
  // per lateral axis (the two axes other than the pull's): min x, min −x.
  std::array<double, 4> minima{
      std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};

  void add_force(double weight, double axial_force) { sums[0] += weight * axial_force; }
  void add_stress(double stress_volume, double volume) {
    sums[1] += stress_volume;
    sums[2] += volume;
  }
  // A member of the gauge's half `h` at `axial` with lateral coordinates
  // `lateral` (the two other axes, in order).
  void add_member(int h, double axial, const std::array<double, 2>& lateral);

  // Of reduced sums: the distance between the halves' centroids, Å.
  [[nodiscard]] double centroid_distance() const;
  // Of reduced sums: the gauge's lateral extents, each plus `spacing`, Å^2.
  [[nodiscard]] double cross_section(double spacing) const;
};

}  // namespace pbms::analysis
