#include "dpd_model.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "kernels/maxwell_boltzmann_velocities.hpp"
#include "kernels/pair_noise.hpp"
#include "kernels/pair_style_registry.hpp"
#include "pbms/error.hpp"
#include "pbms/geometry/lattice_fill.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/io/h5md_reader.hpp"
#include "pbms/io/lammps_data_reader.hpp"
#include "pbms/units.hpp"
#include "pbms/velocity_ramp.hpp"

namespace pbms::dpd {

namespace {

std::map<std::string, DpdParticles>& final_states() {
  static std::map<std::string, DpdParticles> states;
  return states;
}

std::filesystem::path& run_directory() {
  static std::filesystem::path dir;
  return dir;
}

std::filesystem::path final_state_file(const std::string& stage) {
  return run_directory() / stage / "final_state.h5";
}

std::string final_state_identity(const std::string& stage) {
  return fmt::format("the final state of stage '{}'", stage);
}

// id, type, x, v, internal energy.
constexpr std::size_t kFinalStateWidth = 9;

// A stage finished by the run a resumed one continues left its final state
// on disk only.
std::optional<DpdParticles> final_state_from_disk(const std::string& stage) {
  const auto file = final_state_file(stage);
  if (run_directory().empty() || !std::filesystem::exists(file)) return std::nullopt;
  const CheckpointArchive a =
      CheckpointArchive::read(file, final_state_identity(stage), MPI_COMM_SELF);
  const std::vector<double>& rows = a.get("particles");
  DpdParticles p;
  for (std::size_t r = 0; r + kFinalStateWidth <= rows.size(); r += kFinalStateWidth) {
    p.add(static_cast<std::int64_t>(rows[r]), static_cast<int>(rows[r + 1]),
          {rows[r + 2], rows[r + 3], rows[r + 4]}, {rows[r + 5], rows[r + 6], rows[r + 7]});
    p.internal_energy.back() = rows[r + 8];
  }
  return p;
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

void use_run_directory(const std::filesystem::path& dir) {
  run_directory() = dir;
}

void keep_final_state(const std::string& stage, DpdParticles all, bool write) {
  if (write && !run_directory().empty()) {
    std::vector<double> rows;
    rows.reserve(all.size() * kFinalStateWidth);
    for (std::size_t i = 0; i < all.size(); ++i) {
      rows.insert(rows.end(), {static_cast<double>(all.id[i]), static_cast<double>(all.type[i]),
                               all.x[i][0], all.x[i][1], all.x[i][2], all.v[i][0], all.v[i][1],
                               all.v[i][2], all.internal_energy[i]});
    }
    CheckpointArchive a;
    a.put("particles", std::move(rows));
    a.write(final_state_file(stage), final_state_identity(stage));
  }
  final_states()[stage] = std::move(all);
}

namespace {

// An earlier stage's final state, its groups forgotten.
DpdParticles earlier_state(const std::string& from, double mass, const std::string& stage) {
  auto it = final_states().find(from);
  if (it == final_states().end()) {
    if (auto kept = final_state_from_disk(from)) {
      it = final_states().emplace(from, std::move(*kept)).first;
    }
  }
  if (it == final_states().end()) {
    throw Error(fmt::format(
        "stage '{}': initial.from_stage '{}' is not an earlier dpd_run or dpd_equilibrate "
        "stage of this run",
        stage, from));
  }
  DpdParticles particles = it->second;
  particles.mass_per_type = {mass};
  std::fill(particles.group_mask.begin(), particles.group_mask.end(), 0u);
  return particles;
}

// The pieces one after another, each moved by its shift, ids running on.
// A piece is a body with free surfaces: one that crossed a periodic face of
// its own box would be cut in two here, and is refused.
DpdParticles joined_pieces(const std::vector<DpdStageParams::Piece>& pieces, double mass,
                           const std::string& stage) {
  DpdParticles all;
  all.mass_per_type = {mass};
  std::int64_t next_id = 1;
  for (const auto& piece : pieces) {
    const DpdParticles p = earlier_state(piece.from_stage, mass, stage);
    std::int64_t first = std::numeric_limits<std::int64_t>::max(), last = 0;
    for (const auto id : p.id) {
      first = std::min(first, id);
      last = std::max(last, id);
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.image[i] != std::array<int, 3>{0, 0, 0}) {
        throw Error(
            fmt::format("stage '{}': piece '{}' has particles that crossed a periodic "
                        "face of its box; equilibrate it with free surfaces",
                        stage, piece.from_stage));
      }
      Vec3 x = p.x[i];
      for (std::size_t a = 0; a < 3; ++a) x[a] += piece.shift[a];
      all.add(next_id + (p.id[i] - first), p.type[i], x, p.v[i]);
      all.internal_energy.back() = p.internal_energy[i];
    }
    if (!p.id.empty()) next_id += last - first + 1;
  }
  return all;
}

// The particles of an `initial` state; none when there is no `initial`.
DpdParticles initial_particles(const DpdStageParams& p, double mass, const std::string& stage) {
  DpdParticles particles;
  particles.mass_per_type = {mass};
  if (!p.initial) return particles;
  const DpdStageParams::Initial& initial = *p.initial;
  if (!initial.from_stage.empty()) {
    particles = earlier_state(initial.from_stage, mass, stage);
  } else if (!initial.pieces.empty()) {
    particles = joined_pieces(initial.pieces, mass, stage);
  } else if (!initial.h5md.empty()) {
    particles = from_snapshot(read_h5md_particles(initial.h5md), mass);
  } else if (!initial.lammps_data.empty()) {
    particles = from_snapshot(read_lammps_data(initial.lammps_data), mass);
  }
  return particles;
}

// Names a new group (a body or a group): bit g of the masks is name g.
std::uint32_t add_group_name(DpdModel& m, const std::string& name, const std::string& stage) {
  if (std::find(m.group_names.begin(), m.group_names.end(), name) != m.group_names.end()) {
    throw Error(
        fmt::format("stage '{}': the name '{}' is used by two groups or bodies", stage, name));
  }
  if (m.group_names.size() == 32) {
    throw Error(fmt::format("stage '{}': at most 32 groups and bodies", stage));
  }
  m.group_names.push_back(name);
  return 1u << (m.group_names.size() - 1);
}

void fill_bodies(DpdModel& m, const DpdStageParams& p, double lattice_constant,
                 const std::string& stage) {
  std::int64_t next_id = 1;
  for (const auto& b : p.bodies) {
    const std::uint32_t bit = add_group_name(m, b.name, stage);
    const auto sites = geometry::fill_fcc(*b.region, lattice_constant, {}, b.lattice_origin);
    if (sites.empty()) {
      throw Error(fmt::format("stage '{}': body '{}' holds no lattice site", stage, b.name));
    }
    for (const auto& x : sites) {
      m.particles.add(next_id++, 0, x);
      m.particles.group_mask.back() = bit;
    }
  }
}

void mark_groups(DpdModel& m, const DpdStageParams& p, const std::string& stage) {
  for (const auto& g : p.groups) {
    const std::uint32_t bit = add_group_name(m, g.name, stage);
    std::size_t count = 0;
    for (std::size_t i = 0; i < m.particles.size(); ++i) {
      if (g.region->contains(m.particles.x[i])) {
        m.particles.group_mask[i] |= bit;
        ++count;
      }
    }
    if (count == 0) {
      throw Error(fmt::format("stage '{}': group '{}' holds no particle", stage, g.name));
    }
  }
}

// Thermal velocities, then the group behaviours.
void set_motion(DpdModel& m, const DpdStageParams& p, std::uint64_t seed) {
  if (p.temperature > 0.0) assign_maxwell_boltzmann_velocities(m.particles, p.temperature, seed);
  for (const auto& mo : p.motion) {
    const std::uint32_t bit = m.group_mask(mo.group);
    const Vec3 v = mo.velocity;
    const double ramp = mo.ramp_time;
    for (std::size_t i = 0; i < m.particles.size(); ++i) {
      if ((m.particles.group_mask[i] & bit) == 0) continue;
      if (mo.kind == "velocity") {
        for (int a = 0; a < 3; ++a) m.particles.v[i][a] += v[a];
      } else {
        m.particles.v[i] = ramp > 0.0 ? Vec3{0.0, 0.0, 0.0} : v;
      }
    }
    if (mo.kind == "rigid_body") {
      m.rigid_bodies.push_back(bit);
    } else if (mo.kind != "velocity") {
      m.prescribed_mask |= bit;
    }
    if (mo.kind != "velocity") m.group_motions.push_back({bit, v, mo.kind == "rigid_body", ramp});
  }
}

DpdIntegratorSettings integrator_settings(const DpdStageParams& p, std::uint64_t seed) {
  DpdIntegratorSettings s;
  s.scheme = p.scheme == "nve"             ? DpdScheme::kNve
             : p.scheme == "shardlow"      ? DpdScheme::kShardlow
             : p.scheme == "shardlow_dpde" ? DpdScheme::kShardlowDpde
                                           : DpdScheme::kVelocityVerlet;
  s.dt = p.time_step;
  s.skin = p.skin;
  s.friction.gamma = p.gamma;
  s.friction.cutoff = p.dpd_cutoff;
  s.friction.temperature = p.bath_temperature ? *p.bath_temperature : p.temperature;
  s.friction.seed = seed;
  s.friction.noise = pair_noise_distribution(p.noise);
  s.heat_capacity = p.heat_capacity * units::kBoltzmann;
  return s;
}

// DPDE: the internal temperature starts at the kinetic one (or the bath's).
void start_internal_energies(DpdModel& m, double temperature, const std::string& stage) {
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

}  // namespace

DpdModel build_dpd_model(const DpdStageParams& p, const MesoparticleMaterial& material,
                         std::uint64_t seed, const std::string& stage) {
  DpdModel m;
  m.pair = pair_style_from_yaml(material.potential);
  m.box = p.box;
  for (int a = 0; a < 3; ++a) {
    if (!(m.box.hi[a] > m.box.lo[a])) {
      throw Error(fmt::format("stage '{}': box.hi must exceed box.lo on every axis", stage));
    }
  }
  // Particles: lattice-filled bodies, or one existing state.
  if (p.initial && p.initial->keys != 1) {
    throw Error(fmt::format(
        "stage '{}': `initial` takes exactly one of from_stage, h5md, lammps_data, pieces", stage));
  }
  if (p.initial && !p.bodies.empty()) {
    throw Error(fmt::format("stage '{}': give `bodies` or `initial`, not both", stage));
  }
  m.particles = initial_particles(p, material.mass, stage);
  fill_bodies(m, p, material.lattice_constant, stage);
  if (m.particles.size() == 0) {
    throw Error(fmt::format("stage '{}': no particles (give `bodies` or `initial`)", stage));
  }
  mark_groups(m, p, stage);
  set_motion(m, p, seed);
  m.settings = integrator_settings(p, seed);
  if (m.settings.scheme == DpdScheme::kShardlowDpde)
    start_internal_energies(m, p.temperature, stage);
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
