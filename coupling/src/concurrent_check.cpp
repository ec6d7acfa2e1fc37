#include "pbms/coupling/concurrent_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "pbms/config/validator.hpp"
#include "pbms/geometry/region_yaml.hpp"

namespace pbms::coupling {
namespace {

int axis_index(const std::string& a) {
  return a == "x" ? 0 : a == "y" ? 1 : 2;
}

// Bounding boxes that share a volume: a region's particles could belong to
// both, and which solver moves them would depend on the list's order.
void check_regions(const config::StageCheck& c) {
  const YAML::Node regions = c.resolved["regions"];
  std::vector<geometry::Box> boxes;
  for (std::size_t i = 0; i < regions.size(); ++i) {
    boxes.push_back(geometry::region_from_yaml(regions[i]["region"])->bounds());
    for (std::size_t j = 0; j < i; ++j) {
      geometry::Box common;
      for (std::size_t a = 0; a < 3; ++a) {
        common.lo[a] = std::max(boxes[i].lo[a], boxes[j].lo[a]);
        common.hi[a] = std::min(boxes[i].hi[a], boxes[j].hi[a]);
      }
      if (!common.empty() && common.volume() > 0.0) {
        c.validator.error(c.raw["regions"][i], fmt::format("{}.regions[{}]", c.path, i),
                          fmt::format("region '{}' overlaps region '{}'",
                                      regions[i]["name"].Scalar(), regions[j]["name"].Scalar()));
      }
    }
  }
}

void check_grid(const config::StageCheck& c) {
  const YAML::Node g = c.resolved["grid"];
  const double h = g["cell_size"].as<double>();
  const double cutoff = c.resolved["dpd_cutoff"].as<double>();
  const YAML::Node raw = c.raw["grid"];
  if (!(h < cutoff)) {
    c.validator.error(raw["cell_size"], c.path + ".grid.cell_size",
                      fmt::format("the cell edge {:g} Å must be below the DPD cutoff {:g} Å "
                                  "(seed §2.4)",
                                  h, cutoff));
  }
  const auto origin = g["origin"].as<std::vector<double>>();
  const auto cells = g["cells"].as<std::vector<int>>();
  const auto lo = c.resolved["box"]["lo"].as<std::vector<double>>();
  const auto hi = c.resolved["box"]["hi"].as<std::vector<double>>();
  std::array<bool, 3> periodic{};
  for (const auto& a : c.resolved["box"]["periodic"]) {
    periodic[static_cast<std::size_t>(axis_index(a.Scalar()))] = true;
  }
  for (std::size_t a = 0; a < 3; ++a) {
    const double top = origin[a] + cells[a] * h;
    const double tol = 1e-9 * std::max(1.0, std::abs(hi[a] - lo[a]));
    const bool fits = periodic[a]
                          ? std::abs(origin[a] - lo[a]) <= tol && std::abs(top - hi[a]) <= tol
                          : origin[a] <= lo[a] + tol && top >= hi[a] - tol;
    if (cells[a] < 1 || !fits) {
      c.validator.error(raw, c.path + ".grid",
                        fmt::format("the box [{:g}, {:g}] Å along {} does not fit the grid "
                                    "[{:g}, {:g}] Å{}",
                                    lo[a], hi[a], "xyz"[a], origin[a], top,
                                    periodic[a] ? " (a periodic axis must match it exactly)" : ""));
    }
  }
}

void check_interface(const config::StageCheck& c) {
  const std::string scheme = c.resolved["scheme"].Scalar();
  if (scheme != "velocity_verlet" && scheme != "nve") {
    c.validator.error(c.raw["scheme"] ? c.raw["scheme"] : c.raw, c.path + ".scheme",
                      "a concurrent stage moves DPD particles through the grid: scheme "
                      "velocity_verlet or nve");
  }
}

}  // namespace

void check_concurrent_stage(const config::StageCheck& c) {
  check_regions(c);
  check_grid(c);
  check_interface(c);
}

}  // namespace pbms::coupling
