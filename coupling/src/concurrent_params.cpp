#include "pbms/coupling/concurrent_params.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pbms/analysis/baseline_covers.hpp"
#include "pbms/config/axis_name.hpp"
#include "pbms/error.hpp"
#include "pbms/geometry/region_yaml.hpp"
#include "pbms/units.hpp"

namespace pbms::coupling {
namespace {

// A baseline is subtracted sample by sample (analysis::baseline_covers)
// and must hold every slab the speeds time.
void check_baseline(const ConcurrentParams& c) {
  if (c.baseline.empty()) return;
  for (const auto& [side, columns] : c.baseline) {
    const auto t = columns.find("time");
    if (t == columns.end() || !analysis::baseline_covers(t->second, c.steps, c.time_step)) {
      throw Error(fmt::format(
          "wave.baseline.{}: the baseline must be an earlier stage's {}_slabs table over at "
          "least this stage's {} steps of {} ps: run the baseline as long, with the same time_step",
          side, side, c.steps, c.time_step));
    }
  }
  for (const auto& s : c.speeds) {
    for (const auto& slab : {s.near_slab, s.far_slab}) {
      const bool held = std::any_of(c.baseline.begin(), c.baseline.end(),
                                    [&](const auto& b) { return b.second.count(slab) != 0; });
      if (!held) {
        throw Error(
            fmt::format("wave.baseline: slab '{}' of speed '{}' is not in the baseline's "
                        "slabs: the baseline stage must time the same speeds",
                        slab, s.name));
      }
    }
  }
}

using config::axis_index;

InterfaceTreatment treatment(const std::string& name) {
  if (name == "none") return InterfaceTreatment::kNone;
  if (name == "momentum_conserving") return InterfaceTreatment::kMomentumConserving;
  return InterfaceTreatment::kSeed;
}

GasParams gas_from_yaml(const YAML::Node& g, const YAML::Node& box) {
  GasParams gas;
  gas.spacing = g["spacing"].as<double>();
  const auto origin =
      g["origin"] ? g["origin"].as<std::vector<double>>() : box["lo"].as<std::vector<double>>();
  gas.origin = {origin[0], origin[1], origin[2]};
  gas.density = g["density"].as<double>() / units::kGramPerCm3PerAmuPerA3;
  gas.pressure = g["pressure"].as<double>();
  gas.gamma = g["gamma"].as<double>();
  gas.flip = g["flip"].as<double>();
  gas.density_from_grid = g["density_from"].as<std::string>() == "grid";
  gas.heat_bath_time = g["heat_bath_time"].as<double>();
  gas.density_time = g["density_time"].as<double>();
  gas.ramp_time = g["ramp_time"].as<double>();
  gas.clearance = g["clearance"].as<double>(0.75 * gas.spacing);
  gas.probe_distance = g["probe_distance"].as<double>();
  gas.settle_time = g["settle_time"].as<double>();
  gas.walls = g["walls"].as<bool>();
  gas.fields = g["contact"].as<std::string>() == "frictionless" ? GridFields::kFrictionlessContact
                                                                : GridFields::kShared;
  return gas;
}

}  // namespace

bool nests_in(const geometry::Box& inner, const geometry::Box& outer) {
  bool within = true;
  for (std::size_t a = 0; a < 3; ++a) {
    within = within && inner.lo[a] >= outer.lo[a] && inner.hi[a] <= outer.hi[a];
  }
  return within && !(inner == outer);
}

int ConcurrentParams::region_at(const geometry::Vec3& x) const {
  int holder = -1;
  for (std::size_t k = 0; k < regions.size(); ++k) {
    if (!regions[k].region->contains(x)) continue;
    if (holder < 0 || nests_in(regions[k].region->bounds(),
                               regions[static_cast<std::size_t>(holder)].region->bounds())) {
      holder = static_cast<int>(k);
    }
  }
  return holder;
}

Solver ConcurrentParams::solver_at(const geometry::Vec3& x) const {
  const int k = region_at(x);
  return k < 0 ? Solver::kDpd : regions[static_cast<std::size_t>(k)].solver;
}

std::string ConcurrentParams::part(Solver s) const {
  std::vector<std::string> names;
  for (const auto& r : regions) {
    if (r.solver == s) names.push_back(fmt::format("'{}'", r.name));
  }
  const bool dpd = s == Solver::kDpd;
  const std::string what = dpd ? "DPD" : "MPM";
  const std::string gas_text = !dpd && gas ? "the gas around the body" : "";
  if (names.empty()) {
    return gas_text.empty() ? fmt::format("the {} part", what)
                            : fmt::format("the {} part ({})", what, gas_text);
  }
  return fmt::format("the {} part ({} {}{}{})", what, names.size() == 1 ? "region" : "regions",
                     fmt::join(names, ", "), dpd ? " and particles in no region" : "",
                     gas_text.empty() ? "" : " and " + gas_text);
}

ConcurrentParams ConcurrentParams::from_yaml(const YAML::Node& p, const YAML::Node& material) {
  ConcurrentParams c;
  const YAML::Node g = p["grid"];
  const auto origin = g["origin"].as<std::vector<double>>();
  const auto cells = g["cells"].as<std::vector<int>>();
  c.grid = grid::RegularGrid({origin[0], origin[1], origin[2]}, g["cell_size"].as<double>(),
                             {cells[0], cells[1], cells[2]});
  c.flip = g["flip"].as<double>();
  c.move = g["move"].as<std::string>() == "midpoint" ? grid::PointMove::kMidpoint
                                                     : grid::PointMove::kStepStart;
  c.band_margin = g["band_margin"].as<double>();
  for (const auto& a : p["box"]["periodic"]) c.periodic[axis_index(a.as<std::string>())] = true;
  for (const auto& r : p["regions"]) {
    c.regions.push_back({r["name"].as<std::string>(),
                         r["solver"].as<std::string>() == "mpm" ? Solver::kMpm : Solver::kDpd,
                         geometry::region_from_yaml(r["region"])});
  }
  c.interface_name = p["interface"].as<std::string>();
  c.interface = treatment(c.interface_name);
  if (const YAML::Node g = p["ghost_force_correction"]) {
    const double steps = g["average_time"].as<double>() / p["time_step"].as<double>();
    c.ghost_force_steps = std::max<std::int64_t>(1, std::llround(steps));
    if (g["from_stage"]) c.ghost_force_stage = g["from_stage"].as<std::string>();
  }
  if (const YAML::Node e = p["initial_strain"]) {
    const auto v = e.as<std::vector<double>>();
    c.initial_strain = {v[0], v[1], v[2]};
  }
  c.material = p["material"].as<std::string>();
  c.particle_mass = material["mass"].as<double>();
  c.material_lattice_constant = material["lattice_constant"].as<double>();
  for (const auto& m : p["motion"]) {
    const auto kind = m["kind"].as<std::string>();
    if (kind != "rigid" && kind != "frozen") continue;
    HeldGroup h{m["group"].as<std::string>(), {0.0, 0.0, 0.0}};
    if (kind == "rigid") {
      const auto v = m["velocity"].as<std::vector<double>>();
      h.velocity = {v[0], v[1], v[2]};
      h.ramp_time = m["ramp_time"].as<double>(0.0);
    }
    c.held.push_back(h);
  }
  if (const YAML::Node cont = p["continuum"]) {
    if (cont["lattice_constant"]) c.lattice_constant = cont["lattice_constant"].as<double>();
    c.youngs_modulus = cont["youngs_modulus"].as<double>();
    c.poisson_ratio = cont["poisson_ratio"].as<double>();
    c.ddmp = cont["gradient"].as<std::string>("plain") == "ddmp";
  }
  c.time_step = p["time_step"].as<double>();
  c.steps = p["steps"].as<std::int64_t>();
  c.sample_every = p["sample_every"].as<std::int64_t>();
  c.particles_every = p["particles_every"].as<std::int64_t>();
  c.profile_every = p["profile_every"].as<std::int64_t>();
  if (const YAML::Node w = p["wave"]) {
    c.axis = axis_index(w["axis"].as<std::string>());
    c.threshold = w["threshold"].as<double>();
    c.smoothing = w["smoothing"].as<double>();
    c.window = w["window"].as<double>();
    for (const auto& s : w["speeds"]) {
      c.speeds.push_back({s["name"].as<std::string>(), s["near_slab"].as<std::string>(),
                          s["far_slab"].as<std::string>()});
    }
    if (const YAML::Node o = w["opening"]) {
      c.opening =
          std::make_pair(o["dpd_plane"].as<std::string>(), o["mpm_plane"].as<std::string>());
    }
    for (const char* side : {"dpd", "mpm"}) {
      const YAML::Node table = w["baseline"] ? w["baseline"][side] : YAML::Node();
      if (!table) continue;
      for (const auto& column : table) {
        c.baseline[side][column.first.as<std::string>()] =
            column.second["values"].as<std::vector<double>>();
      }
    }
  }
  if (p["noise_of"]) c.noise_of = p["noise_of"].as<std::string>();
  check_baseline(c);
  if (const YAML::Node t = p["tension"]) {
    c.tension = TensionProbe{t["left_grip"].as<std::string>(), t["right_grip"].as<std::string>(),
                             axis_index(t["axis"].as<std::string>()), t["fit_strain"].as<double>()};
  }
  if (const YAML::Node g = p["gas"]) c.gas = gas_from_yaml(g, p["box"]);
  c.necks = necks_from_yaml(p["necks"]);
  c.neck_stable_time = p["neck_stable_time"].as<double>();
  for (const auto& r : p["rods"]) {
    c.rods.push_back({r["name"].as<std::string>(), r["group"].as<std::string>(),
                      axis_index(r["axis"].as<std::string>())});
  }
  if (const YAML::Node t = p["thermostat"]) {
    c.thermostat = std::make_pair(t["temperature"].as<double>(), t["tau"].as<double>());
  }
  if (const YAML::Node v = p["volume"]) {
    c.volume = VolumeProbe{v["group"].as<std::string>(), std::nullopt};
    if (v["reference"]) c.volume->reference = v["reference"].as<double>();
  }
  return c;
}

}  // namespace pbms::coupling
