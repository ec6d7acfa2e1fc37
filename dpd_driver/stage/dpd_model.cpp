#include "dpd_model.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "kernels/maxwell_boltzmann_velocities.hpp"
#include "kernels/pair_noise.hpp"
#include "kernels/pair_style_registry.hpp"
#include "pbms/error.hpp"
#include "pbms/geometry/lattice_fill.hpp"
#include "pbms/geometry/region_yaml.hpp"
#include "pbms/io/h5md_reader.hpp"
#include "pbms/io/lammps_data_reader.hpp"
#include "pbms/units.hpp"
#include "pbms/velocity_ramp.hpp"

namespace pbms::dpd {

namespace {

Vec3 vec3(const YAML::Node& n) {
  const auto v = n.as<std::vector<double>>();
  return {v.at(0), v.at(1), v.at(2)};
}

int axis_index(const std::string& a) {
  return a == "x" ? 0 : a == "y" ? 1 : 2;
}

std::map<std::string, DpdParticles>& final_states() {
  static std::map<std::string, DpdParticles> states;
  return states;
}

DpdParticles from_snapshot(const ParticleSnapshot& s, double mass) {
  DpdParticles p;
  p.mass_per_type = {mass};
  for (std::size_t i = 0; i < s.id.size(); ++i) {
    p.add(s.id[i], 0, s.x[i], s.has_velocities ? s.v[i] : Vec3{0.0, 0.0, 0.0});
    if (!s.image.empty()) p.image.back() = s.image[i];
  }
  return p;
}

}  // namespace

std::uint32_t DpdModel::group_mask(const std::string& name) const {
  for (std::size_t g = 0; g < group_names.size(); ++g) {
    if (group_names[g] == name) return 1u << g;
  }
  throw Error(
      fmt::format("no group or body named '{}' (known: {})", name, fmt::join(group_names, ", ")));
}

std::unique_ptr<PairStyle> pair_style_from_yaml(const YAML::Node& potential) {
  PairStyleParameters params;
  const auto style = potential["style"].as<std::string>();
  for (const auto& kv : potential) {
    const auto key = kv.first.as<std::string>();
    if (key == "style") continue;
    if (key == "file") {
      params.texts[key] = kv.second.as<std::string>();
    } else if (key == "shift") {
      params.numbers[key] = kv.second.as<bool>() ? 1.0 : 0.0;
    } else {
      params.numbers[key] = kv.second.as<double>();
    }
  }
  return PairStyleRegistry::create(style, params);
}

void keep_final_state(const std::string& stage, DpdParticles all) {
  final_states()[stage] = std::move(all);
}

DpdModel build_dpd_model(const YAML::Node& p, const YAML::Node& material, std::uint64_t seed,
                         const std::string& stage) {
  DpdModel m;
  const double mass = material["mass"].as<double>();
  const double lattice_constant = material["lattice_constant"].as<double>();
  m.pair = pair_style_from_yaml(material["potential"]);

  m.box.lo = vec3(p["box"]["lo"]);
  m.box.hi = vec3(p["box"]["hi"]);
  m.box.periodic = {false, false, false};
  for (const auto& a : p["box"]["periodic"]) m.box.periodic[axis_index(a.as<std::string>())] = true;
  for (int a = 0; a < 3; ++a) {
    if (!(m.box.hi[a] > m.box.lo[a])) {
      throw Error(fmt::format("stage '{}': box.hi must exceed box.lo on every axis", stage));
    }
  }

  // Particles: lattice-filled bodies, or one existing state.
  const YAML::Node initial = p["initial"];
  const bool has_bodies = p["bodies"] && p["bodies"].size() > 0;
  if (initial && initial.size() != 1) {
    throw Error(fmt::format(
        "stage '{}': `initial` takes exactly one of from_stage, h5md, lammps_data", stage));
  }
  if (initial && has_bodies) {
    throw Error(fmt::format("stage '{}': give `bodies` or `initial`, not both", stage));
  }
  m.particles.mass_per_type = {mass};
  if (initial && initial["from_stage"]) {
    const auto from = initial["from_stage"].as<std::string>();
    const auto it = final_states().find(from);
    if (it == final_states().end()) {
      throw Error(fmt::format(
          "stage '{}': initial.from_stage '{}' is not an earlier dpd_run or dpd_equilibrate "
          "stage of this run",
          stage, from));
    }
    m.particles = it->second;
    m.particles.mass_per_type = {mass};
    std::fill(m.particles.group_mask.begin(), m.particles.group_mask.end(), 0u);
  } else if (initial && initial["h5md"]) {
    m.particles = from_snapshot(read_h5md_particles(initial["h5md"].as<std::string>()), mass);
  } else if (initial && initial["lammps_data"]) {
    m.particles = from_snapshot(read_lammps_data(initial["lammps_data"].as<std::string>()), mass);
  }
  std::vector<std::pair<std::string, std::unique_ptr<geometry::Region>>> regions;
  auto add_group_name = [&](const std::string& name) {
    if (std::find(m.group_names.begin(), m.group_names.end(), name) != m.group_names.end()) {
      throw Error(
          fmt::format("stage '{}': the name '{}' is used by two groups or bodies", stage, name));
    }
    if (m.group_names.size() == 32) {
      throw Error(fmt::format("stage '{}': at most 32 groups and bodies", stage));
    }
    m.group_names.push_back(name);
  };
  std::int64_t next_id = 1;
  for (const auto& b : p["bodies"]) {
    const auto name = b["name"].as<std::string>();
    add_group_name(name);
    const std::uint32_t bit = 1u << (m.group_names.size() - 1);
    const auto region = geometry::region_from_yaml(b["region"]);
    const auto sites = geometry::fill_fcc(*region, lattice_constant, {}, vec3(b["lattice_origin"]));
    if (sites.empty()) {
      throw Error(fmt::format("stage '{}': body '{}' holds no lattice site", stage, name));
    }
    for (const auto& x : sites) {
      m.particles.add(next_id++, 0, x);
      m.particles.group_mask.back() = bit;
    }
  }
  if (m.particles.size() == 0) {
    throw Error(fmt::format("stage '{}': no particles (give `bodies` or `initial`)", stage));
  }
  for (const auto& g : p["groups"]) {
    const auto name = g["name"].as<std::string>();
    add_group_name(name);
    const std::uint32_t bit = 1u << (m.group_names.size() - 1);
    const auto region = geometry::region_from_yaml(g["region"]);
    std::size_t count = 0;
    for (std::size_t i = 0; i < m.particles.size(); ++i) {
      if (region->contains(m.particles.x[i])) {
        m.particles.group_mask[i] |= bit;
        ++count;
      }
    }
    if (count == 0) {
      throw Error(fmt::format("stage '{}': group '{}' holds no particle", stage, name));
    }
  }

  // Velocities: thermal, then the group behaviours.
  const double temperature = p["temperature"].as<double>();
  if (temperature > 0.0) assign_maxwell_boltzmann_velocities(m.particles, temperature, seed);
  for (const auto& mo : p["motion"]) {
    const std::uint32_t bit = m.group_mask(mo["group"].as<std::string>());
    const auto kind = mo["kind"].as<std::string>();
    const Vec3 v = kind == "frozen" ? Vec3{0.0, 0.0, 0.0} : vec3(mo["velocity"]);
    const double ramp = kind == "rigid" ? mo["ramp_time"].as<double>(0.0) : 0.0;
    for (std::size_t i = 0; i < m.particles.size(); ++i) {
      if ((m.particles.group_mask[i] & bit) == 0) continue;
      if (kind == "velocity") {
        for (int a = 0; a < 3; ++a) m.particles.v[i][a] += v[a];
      } else {
        m.particles.v[i] = ramp > 0.0 ? Vec3{0.0, 0.0, 0.0} : v;
      }
    }
    if (kind == "rigid_body") {
      m.rigid_bodies.push_back(bit);
    } else if (kind != "velocity") {
      m.prescribed_mask |= bit;
    }
    if (kind != "velocity") m.group_motions.push_back({bit, v, kind == "rigid_body", ramp});
  }

  // Integrator.
  const auto scheme = p["scheme"].as<std::string>();
  m.settings.scheme = scheme == "nve"             ? DpdScheme::kNve
                      : scheme == "shardlow"      ? DpdScheme::kShardlow
                      : scheme == "shardlow_dpde" ? DpdScheme::kShardlowDpde
                                                  : DpdScheme::kVelocityVerlet;
  m.settings.dt = p["time_step"].as<double>();
  m.settings.skin = p["skin"].as<double>();
  m.settings.friction.gamma = p["gamma"].as<double>();
  m.settings.friction.cutoff = p["dpd_cutoff"].as<double>();
  m.settings.friction.temperature =
      p["bath_temperature"] ? p["bath_temperature"].as<double>() : temperature;
  m.settings.friction.seed = seed;
  m.settings.friction.noise = pair_noise_distribution(p["noise"].as<std::string>());
  m.settings.heat_capacity = p["heat_capacity"].as<double>() * units::kBoltzmann;
  if (m.settings.scheme == DpdScheme::kShardlowDpde) {
    // Internal temperature starts at the kinetic one (or the bath's).
    const double t0 = temperature > 0.0 ? temperature : m.settings.friction.temperature;
    if (!(t0 > 0.0)) {
      throw Error(
          fmt::format("stage '{}': shardlow_dpde needs temperature > 0 (the start of the internal "
                      "temperatures)",
                      stage));
    }
    for (double& u : m.particles.internal_energy) {
      if (u <= 0.0) u = m.settings.heat_capacity * t0;
    }
  }
  return m;
}

// FNV-1a: a stage's noise stream differs from every other stage's of the
// same run seed, and is the same on every machine.
std::uint64_t stage_seed(std::uint64_t seed, const std::string& stage) {
  std::uint64_t h = 1469598103934665603ULL ^ seed;
  for (const char c : stage) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  return h;
}

std::vector<RampedVelocity> ramped_velocities(const std::vector<DpdModel::GroupMotion>& motions,
                                              std::int64_t step, double dt) {
  std::vector<RampedVelocity> out;
  for (const auto& g : motions) {
    if (g.free_body || !(g.ramp_time > 0.0) || ramp_fraction(step - 1, dt, g.ramp_time) >= 1.0) {
      continue;
    }
    RampedVelocity r{g.mask, g.velocity};
    for (double& c : r.velocity) c *= ramp_fraction(step, dt, g.ramp_time);
    out.push_back(r);
  }
  return out;
}

}  // namespace pbms::dpd
