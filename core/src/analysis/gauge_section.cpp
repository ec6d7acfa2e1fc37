#include "pbms/analysis/gauge_section.hpp"

#include <algorithm>

namespace pbms::analysis {

using config::Param;
using units::Dimension;

Param GaugeSection::param() {
  const GaugeSection d;
  return Param::map(
      "gauge",
      {Param::real_list("section", Dimension::kLength,
                        "Starting axial coordinates [lo, hi] of the gauge's ends, away from the "
                        "grips")
           .require()
           .length(2, 2),
       Param::real("fit_stress_fraction", Dimension::kNone,
                   "The gauge modulus is fitted up to the first sample reaching this fraction "
                   "of the largest smoothed gauge stress")
           .def(d.fit_stress_fraction)
           .above(0)
           .at_most(1)},
      "Also read the Cauchy stress and the strain of a gauge section in the rod's middle "
      "(docs/hierarchy.md): outputs gauge_*");
}

GaugeSection GaugeSection::from_yaml(const YAML::Node& gauge) {
  GaugeSection g;
  const auto s = gauge["section"].as<std::vector<double>>();
  g.lo = std::min(s[0], s[1]);
  g.hi = std::max(s[0], s[1]);
  g.fit_stress_fraction = gauge["fit_stress_fraction"].as<double>();
  return g;
}

double GaugeSection::weight(double x0) const {
  if (x0 <= lo) return 1.0;
  if (x0 >= hi) return 0.0;
  return (hi - x0) / (hi - lo);
}

int GaugeSection::half(double x0) const {
  if (x0 < lo || x0 > hi) return -1;
  return x0 < 0.5 * (lo + hi) ? 0 : 1;
}

void GaugeSums::add_member(int h, double axial, const std::array<double, 2>& lateral) {
  sums[3 + 2 * static_cast<std::size_t>(h)] += 1.0;
  sums[4 + 2 * static_cast<std::size_t>(h)] += axial;
  for (std::size_t k = 0; k < 2; ++k) {
    minima[2 * k] = std::min(minima[2 * k], lateral[k]);
    minima[2 * k + 1] = std::min(minima[2 * k + 1], -lateral[k]);
  }
}

double GaugeSums::centroid_distance() const {
  return sums[6] / std::max(sums[5], 1.0) - sums[4] / std::max(sums[3], 1.0);
}

double GaugeSums::cross_section(double spacing) const {
  return (-minima[1] - minima[0] + spacing) * (-minima[3] - minima[2] + spacing);
}

}  // namespace pbms::analysis
