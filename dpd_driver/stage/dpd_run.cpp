#include "dpd_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

#include <fmt/format.h>

#include "dpd_gauge.hpp"
#include "dpd_model.hpp"
#include "dpd_probes.hpp"
#include "engine/dpd_engine.hpp"
#include "engine/dpd_grid_step.hpp"
#include "pbms/analysis/first_crossing.hpp"
#include "pbms/analysis/front_arrival.hpp"
#include "pbms/analysis/tension_test.hpp"
#include "pbms/error.hpp"
#include "pbms/io/h5md_writer.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/mpi/sorted_rows.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {
namespace {

enum class Mode { kFree, kImpact, kTension, kEquilibrate };

int axis_of(const YAML::Node& n) {
  const auto a = n.as<std::string>();
  return a == "x" ? 0 : a == "y" ? 1 : 2;
}

// The DPD/MPM-grid step of a stage's `grid` map, with the stage's rigid
// groups prescribed on the grid.
std::unique_ptr<DpdGridStep> make_grid_step(DpdEngine& engine, const YAML::Node& grid,
                                            const std::vector<DpdModel::GroupMotion>& motions,
                                            const std::string& stage) {
  if (is_shardlow(engine.settings().scheme)) {
    throw Error(fmt::format(
        "stage '{}': the grid model needs scheme velocity_verlet or nve (a Shardlow sweep "
        "moves the velocities outside the grid step)",
        stage));
  }
  DpdGridSettings s;
  s.cell_size = grid["cell_size"].as<double>();
  s.flip = grid["flip"].as<double>();
  for (const auto& m : motions) s.rigid.push_back({m.mask, m.velocity, m.free_body});
  try {
    return std::make_unique<DpdGridStep>(engine, s);
  } catch (const Error& e) {
    throw Error(fmt::format("stage '{}': {}", stage, e.what()));
  }
}

// The two slabs' histories of an impact and their distance (Å).
struct SlabHistories {
  const std::vector<double>& time;
  const std::vector<double>& near;
  const std::vector<double>& far;
  double distance;
};

// Arrival times, speeds and front velocities of an impact's slabs; where
// the wave did not reach both, the histories are kept and the summary says
// why there is no speed.
void report_impact(const YAML::Node& impact, const SlabHistories& h, StageResults& r) {
  r.add_column("slabs", "time", "ps", h.time);
  r.add_column("slabs", "near_displacement", "Å", h.near);
  r.add_column("slabs", "far_displacement", "Å", h.far);
  const double threshold = impact["threshold"].as<double>();
  const double t_near = analysis::first_crossing(h.time, h.near, threshold);
  const double t_far = analysis::first_crossing(h.time, h.far, threshold);
  if (!(t_far > t_near)) {
    r.attributes["wave_speed"] = fmt::format(
        "not measured: the wave did not reach both slabs (first motion near {:.4g} ps, far "
        "{:.4g} ps); run longer or lower impact.threshold",
        t_near, t_far);
    return;
  }
  // Å/ps is 100 m/s.
  constexpr double kMetresPerSecond = 100.0;
  const double first_motion_speed = h.distance / (t_far - t_near) * kMetresPerSecond;
  r.add_scalar("first_motion_near", t_near, "ps");
  r.add_scalar("first_motion_far", t_far, "ps");
  r.add_scalar("first_motion_speed", first_motion_speed, "m/s");
  const double smoothing = impact["smoothing"].as<double>();
  const double window = impact["window"].as<double>();
  const analysis::FrontArrival near =
      analysis::mid_amplitude_arrival(h.time, h.near, t_near, smoothing, window);
  const analysis::FrontArrival far =
      analysis::mid_amplitude_arrival(h.time, h.far, t_far, smoothing, window);
  const bool mid_amplitude = impact["arrival"].as<std::string>() == "mid_amplitude";
  if (far.time > near.time) {
    const double speed = h.distance / (far.time - near.time) * kMetresPerSecond;
    r.add_scalar("mid_amplitude_speed", speed, "m/s");
    r.add_scalar("front_near", near.time, "ps");
    r.add_scalar("front_far", far.time, "ps");
    r.add_scalar("front_velocity_near", near.amplitude * kMetresPerSecond, "m/s");
    r.add_scalar("front_velocity_far", far.amplitude * kMetresPerSecond, "m/s");
    r.add_scalar("particle_velocity", 0.5 * (near.amplitude + far.amplitude) * kMetresPerSecond,
                 "m/s");
    if (mid_amplitude) r.add_scalar("wave_speed", speed, "m/s");
  } else if (mid_amplitude) {
    r.attributes["wave_speed"] = fmt::format(
        "not measured: no mid-amplitude arrival at both slabs (near {:.4g} ps, far {:.4g} ps)",
        near.time, far.time);
  }
  if (!mid_amplitude) r.add_scalar("wave_speed", first_motion_speed, "m/s");
}

void run_stage(StageContext& ctx, Mode mode) {
  const YAML::Node& p = ctx.params();
  const int rank = ctx.rank();
  const YAML::Node material = ctx.material(p["material"].as<std::string>());
  DpdModel model = build_dpd_model(p, material, stage_seed(ctx.seed(), ctx.stage()), ctx.stage());
  const double lattice_constant = material["lattice_constant"].as<double>();
  const std::uint32_t prescribed = model.prescribed_mask;
  const std::vector<std::uint32_t> rigid_bodies = model.rigid_bodies;
  const auto group_motions = model.group_motions;
  const analysis::TensionTest tension_test = mode == Mode::kTension && p["tension"]
                                                 ? analysis::TensionTest::from_yaml(p["tension"])
                                                 : analysis::TensionTest{};
  std::unique_ptr<DpdGauge> gauge;
  if (tension_test.gauge) {
    gauge = std::make_unique<DpdGauge>(*tension_test.gauge, model.particles,
                                       model.group_mask(p["tension"]["specimen"].as<std::string>()),
                                       axis_of(p["tension"]["axis"]), 0.5 * lattice_constant);
  }
  DpdEngine engine(ctx.comm(), model.box, std::move(model.pair), model.settings,
                   std::move(model.particles));
  engine.set_prescribed_groups(prescribed);
  engine.set_rigid_bodies(rigid_bodies);
  std::unique_ptr<DpdGridStep> grid_step;
  if (p["grid"]) grid_step = make_grid_step(engine, p["grid"], group_motions, ctx.stage());

  const auto steps = p["steps"].as<std::int64_t>();
  const auto sample_every = p["sample_every"].as<std::int64_t>();
  const auto particles_every = p["particles_every"].as<std::int64_t>();
  const bool write_forces = p["write_forces"].as<bool>();
  const bool write_u = p["write_internal_energy"].as<bool>();
  const double dt = model.settings.dt;
  const double target_t = mode == Mode::kEquilibrate ? p["target_temperature"].as<double>() : 0.0;
  const double tau = mode == Mode::kEquilibrate ? p["tau"].as<double>() : 0.0;

  DpdProbes probes(p["probes"], model);
  std::vector<std::vector<double>> samples(probes.columns().size());
  std::vector<double> sample_step, sample_time, temperatures;

  // Impact: the two slabs' centre-of-mass displacement along the axis.
  std::uint32_t near_mask = 0, far_mask = 0;
  int impact_axis = 0;
  Vec3 near0{}, far0{};
  std::vector<double> slab_t, near_s, far_s;
  if (mode == Mode::kImpact) {
    if (!p["impact"])
      throw Error(fmt::format("stage '{}': mode impact needs `impact`", ctx.stage()));
    near_mask = model.group_mask(p["impact"]["near_slab"].as<std::string>());
    far_mask = model.group_mask(p["impact"]["far_slab"].as<std::string>());
    impact_axis = axis_of(p["impact"]["axis"]);
    near0 = DpdProbes::centre_of_mass(engine, near_mask);
    far0 = DpdProbes::centre_of_mass(engine, far_mask);
  }
  // Tension: specimen length and conservative virial stress.
  std::uint32_t specimen_mask = 0;
  int tension_axis = 0;
  double area = 0.0, length0 = 0.0;
  std::vector<double> strain, stress, grip_stress;
  std::uint32_t left_grip = 0, right_grip = 0;
  if (mode == Mode::kTension) {
    if (!p["tension"]) {
      throw Error(fmt::format("stage '{}': mode tension needs `tension`", ctx.stage()));
    }
    specimen_mask = model.group_mask(p["tension"]["specimen"].as<std::string>());
    if (const YAML::Node grips = p["tension"]["grips"]) {
      left_grip = model.group_mask(grips["left"].as<std::string>());
      right_grip = model.group_mask(grips["right"].as<std::string>());
    }
    tension_axis = axis_of(p["tension"]["axis"]);
    // An fcc crystal of n cells spans n a; its outermost sites, n a − a/2.
    const double plane = 0.5 * lattice_constant;
    length0 = DpdProbes::extent(engine, specimen_mask, tension_axis) + plane;
    if (p["tension"]["area"]) {
      area = p["tension"]["area"].as<double>();
    } else {
      area = 1.0;
      for (int a = 0; a < 3; ++a) {
        if (a != tension_axis) area *= DpdProbes::extent(engine, specimen_mask, a) + plane;
      }
    }
  }

  // H5MD trajectory: every rank writes the particles it holds, each at the
  // row of its id, so no rank gathers them.
  std::unique_ptr<H5mdWriter> h5md;
  const OrthogonalBox& box = engine.domain().box();
  const std::array<double, 3> edges{box.length(0), box.length(1), box.length(2)};
  const std::size_t width = 8 + (write_forces ? 3 : 0) + (write_u ? 1 : 0);
  auto local_rows = [&]() {
    const DpdParticles& q = engine.particles();
    std::vector<double> rows;
    rows.reserve(engine.owned() * width);
    for (std::size_t i = 0; i < engine.owned(); ++i) {
      rows.insert(rows.end(), {static_cast<double>(q.id[i]), static_cast<double>(q.type[i]),
                               q.x[i][0], q.x[i][1], q.x[i][2], q.v[i][0], q.v[i][1], q.v[i][2]});
      if (write_forces) rows.insert(rows.end(), {q.f[i][0], q.f[i][1], q.f[i][2]});
      if (write_u) rows.push_back(q.internal_energy[i]);
    }
    return rows;
  };
  auto write_frame = [&](std::int64_t step) {
    const DpdParticles& q = engine.particles();
    const auto n = static_cast<std::ptrdiff_t>(engine.owned());
    const std::vector<std::int64_t> ids(q.id.begin(), q.id.begin() + n);
    if (!h5md) {
      H5mdWriter::Options o;
      o.path = (ctx.stage_dir() / "particles.h5md").string();
      o.creator_version = "dpd_driver";
      o.periodic = box.periodic;
      o.velocities = true;
      o.forces = write_forces;
      o.internal_energy = write_u;
      h5md = std::make_unique<H5mdWriter>(ctx.comm(), o, ids,
                                          std::vector<int>(q.type.begin(), q.type.begin() + n));
    }
    auto flat = [n](const std::vector<Vec3>& a) {
      std::vector<double> out;
      out.reserve(3 * static_cast<std::size_t>(n));
      for (auto it = a.begin(); it != a.begin() + n; ++it)
        out.insert(out.end(), it->begin(), it->end());
      return out;
    };
    const std::vector<double> u =
        write_u ? std::vector<double>(q.internal_energy.begin(), q.internal_energy.begin() + n)
                : std::vector<double>{};
    h5md->write_frame(step, static_cast<double>(step) * dt, edges, ids, flat(q.x), flat(q.v),
                      write_forces ? flat(q.f) : std::vector<double>{}, u);
  };

  ThermoState thermo;
  auto sample = [&](std::int64_t step) {
    thermo = engine.thermo(probes.needs_potential() || mode == Mode::kTension);
    const auto values = probes.sample(engine, thermo);
    for (std::size_t c = 0; c < values.size(); ++c) samples[c].push_back(values[c]);
    const double t = static_cast<double>(step) * dt;
    sample_step.push_back(static_cast<double>(step));
    sample_time.push_back(t);
    if (step > 0) temperatures.push_back(thermo.temperature);
    if (mode == Mode::kTension) {
      const double length =
          DpdProbes::extent(engine, specimen_mask, tension_axis) + 0.5 * lattice_constant;
      strain.push_back((length - length0) / length0);
      // Tension positive: σ = −W / V, eV/Å^3 to GPa.
      stress.push_back(-thermo.virial[static_cast<std::size_t>(tension_axis)] / (area * length) *
                       units::kBarPerEvPerA3 / units::kBarPerGPa);
      if (gauge) gauge->sample(engine);
      if (left_grip != 0) {
        const auto a = static_cast<std::size_t>(tension_axis);
        const double pull = 0.5 * (DpdProbes::group_force(engine, left_grip)[a] -
                                   DpdProbes::group_force(engine, right_grip)[a]);
        grip_stress.push_back(pull / area * units::kBarPerEvPerA3 / units::kBarPerGPa);
      }
    }
  };
  auto track_slabs = [&](std::int64_t step) {
    const Vec3 a = DpdProbes::centre_of_mass(engine, near_mask);
    const Vec3 b = DpdProbes::centre_of_mass(engine, far_mask);
    slab_t.push_back(static_cast<double>(step) * dt);
    near_s.push_back(a[impact_axis] - near0[impact_axis]);
    far_s.push_back(b[impact_axis] - far0[impact_axis]);
  };

  sample(0);
  const ThermoState initial = thermo.potential != 0.0 ? thermo : engine.thermo(true);
  if (mode == Mode::kImpact) track_slabs(0);
  if (particles_every > 0 || steps == 0) write_frame(0);
  const auto started = std::chrono::steady_clock::now();
  // Grips on a velocity ramp take each step's speed before it.
  auto ramp_grips = [&](std::int64_t n) {
    for (const auto& r : ramped_velocities(group_motions, n, dt)) {
      if (grid_step) {
        grid_step->set_rigid_velocity(r.mask, r.velocity);
      } else {
        engine.set_group_velocity(r.mask, r.velocity);
      }
    }
  };
  for (std::int64_t n = 1; n <= steps; ++n) {
    set_current_step(n);
    ramp_grips(n);
    if (grid_step) {
      grid_step->step();
    } else {
      engine.step();
    }
    if (mode == Mode::kEquilibrate) engine.berendsen(target_t, tau);
    if (mode == Mode::kImpact) track_slabs(n);
    if (n % sample_every == 0 || n == steps) sample(n);
    if ((particles_every > 0 && n % particles_every == 0) || n == steps) write_frame(n);
    ctx.progress(n, steps, static_cast<double>(n) * dt, "dpd");
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const ThermoState last = engine.thermo(true);

  // The final state, for a later stage's initial.from_stage.
  {
    const auto all = mpi::sorted_rows(ctx.comm(), local_rows(), width, mpi::RowsTo::kEveryRank);
    DpdParticles state;
    state.mass_per_type = engine.particles().mass_per_type;
    for (std::size_t r = 0; r + width <= all.size(); r += width) {
      state.add(static_cast<std::int64_t>(all[r]), static_cast<int>(all[r + 1]),
                {all[r + 2], all[r + 3], all[r + 4]}, {all[r + 5], all[r + 6], all[r + 7]});
      if (write_u) state.internal_energy.back() = all[r + width - 1];
    }
    if (!write_u) {
      // Internal energies travel only when written; carry them otherwise too.
      std::vector<double> rows;
      const DpdParticles& q = engine.particles();
      for (std::size_t i = 0; i < engine.owned(); ++i) {
        rows.insert(rows.end(), {static_cast<double>(q.id[i]), q.internal_energy[i]});
      }
      const auto u = mpi::sorted_rows(ctx.comm(), rows, 2, mpi::RowsTo::kEveryRank);
      for (std::size_t r = 0; r < state.size(); ++r) state.internal_energy[r] = u[2 * r + 1];
    }
    keep_final_state(ctx.stage(), std::move(state));
  }

  auto& r = ctx.results();
  r.add_scalar("steps", static_cast<double>(steps), "1");
  r.add_scalar("particles", static_cast<double>(engine.total_particles()), "1");
  r.add_scalar("temperature", last.temperature, "K");
  if (!temperatures.empty()) {
    r.add_scalar("mean_temperature",
                 std::accumulate(temperatures.begin(), temperatures.end(), 0.0) /
                     static_cast<double>(temperatures.size()),
                 "K");
  }
  r.add_scalar("potential_energy", last.potential, "eV");
  r.add_scalar("total_energy", last.total(), "eV");
  r.add_scalar("energy_drift",
               (last.total() - initial.total()) / std::max(std::abs(initial.total()), 1e-300), "1");
  r.add_scalar("pressure", (last.pressure[0] + last.pressure[1] + last.pressure[2]) / 3.0, "bar");
  if (steps > 0 && seconds > 0.0) {
    r.add_scalar("steps_per_second", static_cast<double>(steps) / seconds, "1/s");
  }
  r.add_column("probes", "step", "1", sample_step);
  r.add_column("probes", "time", "ps", sample_time);
  for (std::size_t c = 0; c < samples.size(); ++c) {
    r.add_column("probes", probes.columns()[c], probes.units()[c], samples[c]);
  }
  if (mode == Mode::kImpact) {
    report_impact(p["impact"],
                  {slab_t, near_s, far_s, std::abs(far0[impact_axis] - near0[impact_axis])}, r);
  }
  if (mode == Mode::kTension) {
    tension_test.report(r, strain, stress, ctx.stage());
    if (left_grip != 0) tension_test.report_grips(r, strain, stress, grip_stress, ctx.stage());
    if (gauge) gauge->report(tension_test, r, ctx.stage());
    r.attributes["cross_section_A2"] = fmt::format("{:.6g}", area);
  }
  r.attributes["decomposition"] = fmt::format("{}x{}x{}", engine.domain().dims()[0],
                                              engine.domain().dims()[1], engine.domain().dims()[2]);
  r.attributes["neighbour_list_builds"] = fmt::format("{}", engine.rebuilds());
  if (grid_step)
    r.attributes["grid_cell_size"] = fmt::format("{:g}", grid_step->grid().cell_size());
  if (h5md && rank == 0)
    r.files.push_back((std::filesystem::path(ctx.stage()) / "particles.h5md").string());
}

}  // namespace

void DpdRunStage::run(StageContext& ctx) {
  const auto mode = ctx.params()["mode"].as<std::string>();
  run_stage(ctx, mode == "impact"    ? Mode::kImpact
                 : mode == "tension" ? Mode::kTension
                                     : Mode::kFree);
}

void DpdEquilibrateStage::run(StageContext& ctx) {
  run_stage(ctx, Mode::kEquilibrate);
}

}  // namespace pbms::dpd
