#include "pbms/coupling/concurrent_check.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "pbms/analysis/quasi_static_pull.hpp"
#include "pbms/config/axis_name.hpp"
#include "pbms/config/validator.hpp"
#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/geometry/region_yaml.hpp"
#include "pbms/units.hpp"

namespace pbms::coupling {
namespace {

using config::axis_index;

// Bounding boxes that share a volume without one holding the other: a
// particle there could belong to both, and which solver moves it would
// depend on the list's order. A region nested in another (a core in a
// shell) is fine: the inner one's solver wins inside it.
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
      const bool nested = nests_in(boxes[i], boxes[j]) || nests_in(boxes[j], boxes[i]);
      if (!common.empty() && common.volume() > 0.0 && !nested) {
        c.validator.error(c.raw["regions"][i], fmt::format("{}.regions[{}]", c.path, i),
                          fmt::format("region '{}' overlaps region '{}' without one holding the "
                                      "other (regions may nest: the inner one's solver wins)",
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

// The MPM points of a region need the continuum's material; a body all
// DPD (in a gas, say) needs none.
void check_continuum_given(const config::StageCheck& c) {
  if (c.resolved["continuum"]) return;
  const YAML::Node regions = c.resolved["regions"];
  for (std::size_t i = 0; i < regions.size(); ++i) {
    if (regions[i]["solver"].Scalar() != "mpm") continue;
    c.validator.error(c.raw["regions"][i], fmt::format("{}.regions[{}]", c.path, i),
                      fmt::format("region '{}' is MPM, and its points need a material: add "
                                  "`continuum` (youngs_modulus, poisson_ratio)",
                                  regions[i]["name"].Scalar()));
  }
}

// A modulus given as a number far from any solid's is a unit slip: a bare
// number is bar (metal units), so `98` meant as GPa is 1e4 times too soft.
void check_continuum(const config::StageCheck& c) {
  const YAML::Node raw = c.raw["continuum"];
  const YAML::Node cont = c.resolved["continuum"];
  if (!raw || !raw.IsMap()) return;
  constexpr double kBarPerGpa = 1.0e4;
  const YAML::Node e = raw["youngs_modulus"];
  if (e && e.IsScalar()) {
    const double gpa = cont["youngs_modulus"].as<double>() / kBarPerGpa;
    if (gpa < 1.0 || gpa > 2000.0) {
      c.validator.error(e, c.path + ".continuum.youngs_modulus",
                        fmt::format("{:g} GPa is no solid's Young's modulus (1 to 2,000 GPa); a "
                                    "bare number is bar: write the unit, e.g. `98 GPa`",
                                    gpa));
    }
  }
  const YAML::Node a = raw["lattice_constant"];
  const YAML::Node material = c.materials[c.resolved["material"].Scalar()];
  if (a && a.IsScalar() && material && material["lattice_constant"]) {
    const double given = cont["lattice_constant"].as<double>();
    const double own = material["lattice_constant"].as<double>();
    const double off = std::abs(given / own - 1.0);
    if (off > 0.03 && off <= 0.1) {
      c.validator.warn(
          a, c.path + ".continuum.lattice_constant",
          fmt::format("{:g} Å is {:.1f} % off the material's own {:g} Å: the MPM points would be "
                      "{:.1f} % {} dense than its DPD particles, and the interface would pass a "
                      "step in density; thermal expansion to 1,000 K is below 2 %",
                      given, 100.0 * (given / own - 1.0), own,
                      100.0 * std::abs(std::pow(own / given, 3.0) - 1.0),
                      given > own ? "less" : "more"));
    }
    if (off > 0.1) {
      c.validator.error(
          a, c.path + ".continuum.lattice_constant",
          fmt::format("{:g} Å is {:.0f} % off the material's own {:g} Å: the MPM "
                      "points stand on the mesoparticle lattice (an atomic lattice "
                      "constant would make them {:.0f} times too light)",
                      given, 100.0 * (given / own - 1.0), own, std::pow(own / given, 3.0)));
    }
  }
}

// A grip's motion along the pull: its velocity (zero when frozen) and the
// time of its linear ramp to it.
struct GripMotion {
  double speed = 0.0;
  double ramp_time = 0.0;

  // How far the grip has moved after `time` ps.
  [[nodiscard]] double travel(double time) const {
    if (time >= ramp_time) return speed * (time - 0.5 * ramp_time);
    return speed * time * time / (2.0 * ramp_time);
  }
};

// Nothing for a grip that no motion entry names.
std::optional<GripMotion> grip_motion(const config::StageCheck& c, const std::string& grip,
                                      int axis) {
  for (const auto& m : c.resolved["motion"]) {
    if (m["group"].Scalar() != grip) continue;
    if (m["kind"].Scalar() == "frozen" || !m["velocity"]) return GripMotion{};
    return GripMotion{m["velocity"][axis].as<double>(),
                      m["ramp_time"] ? m["ramp_time"].as<double>() : 0.0};
  }
  return std::nullopt;
}

// Grips that do not pull apart give a tension test no strain: E is NaN.
void check_grips(const config::StageCheck& c) {
  const YAML::Node t = c.resolved["tension"];
  if (!t || !t.IsMap()) return;
  const YAML::Node raw = c.raw["tension"];
  const std::string left = t["left_grip"].Scalar(), right = t["right_grip"].Scalar();
  if (left == right) {
    c.validator.error(raw["right_grip"], c.path + ".tension.right_grip",
                      fmt::format("the right grip is the left grip ('{}'): name two groups at "
                                  "the rod's two ends",
                                  left));
    return;
  }
  const int axis = axis_index(t["axis"].as<std::string>("x"));
  const auto l = grip_motion(c, left, axis), r = grip_motion(c, right, axis);
  if (l && r && !(r->speed - l->speed > 0.0)) {
    c.validator.error(raw, c.path + ".tension",
                      fmt::format("the grips do not pull the rod apart: '{}' moves at {:g} and "
                                  "'{}' at {:g} Å/ps along {} (the right one must be faster)",
                                  left, l->speed, right, r->speed, "xyz"[axis]));
  }
}

geometry::RegionPtr group_region(const config::StageCheck& c, const std::string& name) {
  for (const auto& g : c.resolved["groups"]) {
    if (g["name"].Scalar() == name) return geometry::region_from_yaml(g["region"]);
  }
  return nullptr;
}

// The pull must be slow against the rod's sideways contraction for its
// slope to be Young's modulus (analysis::check_quasi_static, which judges
// the run's own fitted E the same way); here the continuum's E stands for
// it, and the grips' lateral span for the rod's width.
void warn_fast_pull(const config::StageCheck& c, double width, double opening,
                    const GripMotion& left, const GripMotion& right, double run_time) {
  const YAML::Node cont = c.resolved["continuum"];
  const YAML::Node material = c.materials[c.resolved["material"].Scalar()];
  // A `{from: ...}` modulus is known only at run time, where the run's own
  // fitted E is judged.
  const auto scalar = [](const YAML::Node& n) { return n && n.IsScalar(); };
  if (!cont || !scalar(cont["youngs_modulus"]) || !material || !scalar(material["mass"]) ||
      !scalar(material["lattice_constant"])) {
    return;
  }
  // When the grips have opened by `opening`: the end of the fit window.
  double lo = 0.0, hi = run_time;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (right.travel(mid) - left.travel(mid) < opening ? lo : hi) = mid;
  }
  const double a = scalar(cont["lattice_constant"]) ? cont["lattice_constant"].as<double>()
                                                    : material["lattice_constant"].as<double>();
  const double density = 4.0 * material["mass"].as<double>() / (a * a * a);
  const double gpa = cont["youngs_modulus"].as<double>() / units::kBarPerGPa;
  const double periods = analysis::lateral_periods(gpa, density, width, hi);
  if (!(periods < analysis::kQuasiStaticPeriods)) return;
  c.validator.warn(
      c.raw["tension"], c.path + ".tension.fit_strain",
      fmt::format("the grips reach fit_strain {:g} after {:.3g} ps, {:.2g} of the time a bar "
                  "wave at the continuum's {:g} GPa takes to cross the {:.4g} Å wide rod and "
                  "come back: the rod would have no time to contract sideways, and "
                  "youngs_modulus would measure a stiffer, uniaxial-strain response; pull more "
                  "slowly or fit to a larger strain",
                  c.resolved["tension"]["fit_strain"].as<double>(), hi, periods, gpa, width));
}

// E is the slope up to fit_strain: a run that stops short of it has no
// fit window, and E came out NaN. The length is the grips' outer span (a
// little above the body's), so the estimate errs on the side of passing.
void check_fit_window(const config::StageCheck& c) {
  const YAML::Node t = c.resolved["tension"];
  if (!t || !t.IsMap()) return;
  const std::string left = t["left_grip"].Scalar(), right = t["right_grip"].Scalar();
  const auto l = group_region(c, left), r = group_region(c, right);
  const int axis = axis_index(t["axis"].as<std::string>("x"));
  const double time = c.resolved["steps"].as<double>() * c.resolved["time_step"].as<double>();
  const auto ml = grip_motion(c, left, axis), mr = grip_motion(c, right, axis);
  if (!l || !r || !ml || !mr) return;
  const double dl = ml->travel(time), dr = mr->travel(time);
  const auto a = static_cast<std::size_t>(axis);
  const double length = r->bounds().hi[a] - l->bounds().lo[a];
  const double reached = (dr - dl) / length;
  const double fit = t["fit_strain"].as<double>();
  // Grips that are one group or do not pull apart are check_grips's to report.
  if (left == right || !(dr > dl) || !(length > 0.0)) return;
  if (fit <= reached) {
    double width = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      if (k != a) width = std::max(width, r->bounds().hi[k] - r->bounds().lo[k]);
    }
    warn_fast_pull(c, width, fit * length, *ml, *mr, time);
    return;
  }
  c.validator.error(c.raw["tension"], c.path + ".tension.fit_strain",
                    fmt::format("fit_strain {:g} is beyond the strain the grips reach: they move "
                                "{:.3g} Å apart in {:g} ps over a rod of about {:.4g} Å, {:.3g}; "
                                "run longer or fit to a smaller strain",
                                fit, dr - dl, time, length, reached));
}

// A grip moves its planes rigidly: an opening measured on them is the
// grip's, not the interface's.
void check_opening_off_grips(const config::StageCheck& c) {
  const YAML::Node t = c.resolved["tension"];
  const YAML::Node w = c.resolved["wave"];
  if (!t || !t.IsMap() || !w || !w["opening"]) return;
  for (const char* plane : {"dpd_plane", "mpm_plane"}) {
    const auto p = group_region(c, w["opening"][plane].Scalar());
    for (const char* grip : {"left_grip", "right_grip"}) {
      const auto g = group_region(c, t[grip].Scalar());
      if (!p || !g) continue;
      const geometry::Box a = p->bounds(), b = g->bounds();
      bool apart = false;
      for (std::size_t k = 0; k < 3; ++k) apart = apart || a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k];
      if (apart) continue;
      c.validator.error(c.raw["wave"]["opening"][plane], c.path + ".wave.opening." + plane,
                        fmt::format("the opening plane '{}' overlaps the grip '{}': a grip "
                                    "moves rigidly, so the opening would be the grip's",
                                    w["opening"][plane].Scalar(), t[grip].Scalar()));
    }
  }
}

}  // namespace

// A strained start needs its ghost forces measured on the unstrained body
// (an earlier stage); an earlier stage named for them must measure some.
void check_ghost_forces(const config::StageCheck& c) {
  const YAML::Node g = c.resolved["ghost_force_correction"];
  if (!g) return;
  const YAML::Node raw = c.raw["ghost_force_correction"];
  const std::string path = c.path + ".ghost_force_correction";
  if (!g["from_stage"]) {
    const double window = g["average_time"].as<double>();
    const double run = c.resolved["steps"].as<double>() * c.resolved["time_step"].as<double>();
    if (window > run) {
      c.validator.error(raw["average_time"], path + ".average_time",
                        fmt::format("{} ps is longer than the stage ({} ps): the dead loads "
                                    "would never be measured",
                                    window, run));
    }
    const auto e = c.resolved["initial_strain"].as<std::vector<double>>();
    if (e[0] != 0.0 || e[1] != 0.0 || e[2] != 0.0) {
      c.validator.error(raw, path,
                        "with an initial_strain the dead loads must come from_stage (an earlier "
                        "stage of the unstrained body): measured here, they would hold the "
                        "strain's own tractions and undo its stress");
    }
    return;
  }
  const std::string from = g["from_stage"].as<std::string>();
  const YAML::Node earlier = config::stage_named(c.workflow, from);
  if (earlier && !earlier["ghost_force_correction"]) {
    c.validator.error(raw["from_stage"], path + ".from_stage",
                      fmt::format("stage '{}' measures no ghost forces (it has no "
                                  "ghost_force_correction)",
                                  from));
  }
}

// The ramp raises the gas's pressure through its heat bath.
void check_gas_ramp(const config::StageCheck& c) {
  const YAML::Node g = c.resolved["gas"];
  if (!g || !(g["ramp_time"].as<double>() > 0.0) || g["heat_bath_time"].as<double>() > 0.0) return;
  c.validator.error(c.raw["gas"]["ramp_time"], c.path + ".gas.ramp_time",
                    "the ramp raises the gas's pressure through its heat bath: give "
                    "gas.heat_bath_time > 0, or leave ramp_time out");
}

// Frictionless contact gives the MPM program's points a velocity of their
// own: an MPM region of the body would come apart from its DPD region.
void check_gas_contact(const config::StageCheck& c) {
  const YAML::Node g = c.resolved["gas"];
  if (!g || g["contact"].as<std::string>() != "frictionless") return;
  const YAML::Node regions = c.resolved["regions"];
  for (std::size_t i = 0; i < regions.size(); ++i) {
    if (regions[i]["solver"].as<std::string>() != "mpm") continue;
    c.validator.error(c.raw["gas"]["contact"], c.path + ".gas.contact",
                      fmt::format("frictionless contact needs the body all DPD: region '{}' is "
                                  "MPM, and its points would slide on the DPD part as the gas "
                                  "does (use shared_velocity)",
                                  regions[i]["name"].Scalar()));
    return;
  }
}

// Points on fewer than half the cells leave the grid holes that a point
// crossing a cell face jumps across: measured on the impact bar at rest
// all MPM (298 K, 5.5 ps), its energy held on cells of 4.0 Å (0.69 points
// a cell), grew by half on 3.0 Å (0.29) and fourfold on 2.4 Å (0.15).
constexpr double kFewestPointsPerCell = 0.5;

void warn_sparse_points(const config::StageCheck& c) {
  const double h = c.resolved["grid"]["cell_size"].as<double>();
  const YAML::Node at =
      c.raw["grid"] && c.raw["grid"]["cell_size"] ? c.raw["grid"]["cell_size"] : c.raw["grid"];
  const auto warn = [&](const std::string& what, double per_cell, double fewest_h) {
    c.validator.warn(at, c.path + ".grid.cell_size",
                     fmt::format("cells of {:g} Å hold {:.2g} {} a cell: with points in fewer "
                                 "than half the cells, a point crossing a cell face pumps "
                                 "energy into the grid (an MPM bar at rest gained half its "
                                 "energy in 5.5 ps at 0.29 a cell); use cells of at least {:.4g} Å",
                                 h, per_cell, what, fewest_h));
  };
  const YAML::Node material = c.materials[c.resolved["material"].Scalar()];
  const YAML::Node cont = c.resolved["continuum"];
  const bool any_mpm =
      std::any_of(c.resolved["regions"].begin(), c.resolved["regions"].end(),
                  [](const YAML::Node& r) { return r["solver"].Scalar() == "mpm"; });
  if (any_mpm && material && material["lattice_constant"]) {
    const double a = cont && cont["lattice_constant"] && cont["lattice_constant"].IsScalar()
                         ? cont["lattice_constant"].as<double>()
                         : material["lattice_constant"].as<double>();
    // Four points a cubic cell of the fcc lattice.
    const double per_cell = 4.0 * std::pow(h / a, 3.0);
    if (per_cell < kFewestPointsPerCell) {
      warn("of the MPM region's points", per_cell, a * std::cbrt(kFewestPointsPerCell / 4.0));
    }
  }
  const YAML::Node gas = c.resolved["gas"];
  if (gas && gas["spacing"] && gas["spacing"].IsScalar()) {
    const double spacing = gas["spacing"].as<double>();
    const double per_cell = std::pow(h / spacing, 3.0);
    if (per_cell < kFewestPointsPerCell) {
      warn("of the gas's points", per_cell, spacing * std::cbrt(kFewestPointsPerCell));
    }
  }
}

void check_concurrent_stage(const config::StageCheck& c) {
  check_regions(c);
  check_grid(c);
  check_interface(c);
  check_continuum_given(c);
  check_continuum(c);
  check_grips(c);
  check_opening_off_grips(c);
  check_fit_window(c);
  check_ghost_forces(c);
  check_gas_ramp(c);
  check_gas_contact(c);
  warn_sparse_points(c);
}

}  // namespace pbms::coupling
