#include "dpd_run.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>

#include <fmt/format.h>

#include "dpd_impact_analysis.hpp"
#include "dpd_model.hpp"
#include "dpd_particle_view.hpp"
#include "dpd_probes.hpp"
#include "dpd_run_params.hpp"
#include "dpd_tension_analysis.hpp"
#include "dpd_trajectory.hpp"
#include "engine/dpd_engine.hpp"
#include "engine/dpd_grid_step.hpp"
#include "engine_checkpoint.hpp"
#include "neck_probe.hpp"
#include "pbms/analysis/baseline_covers.hpp"
#include "pbms/driver/stage_checkpoints.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {
namespace {

using Mode = DpdRunParams::Mode;

// The DPD/MPM-grid step of a stage's `grid` map, with the stage's rigid
// groups prescribed on the grid.
std::unique_ptr<DpdGridStep> make_grid_step(DpdEngine& engine, const DpdStageParams::Grid& grid,
                                            const std::vector<DpdModel::GroupMotion>& motions,
                                            const std::string& stage) {
  if (is_shardlow(engine.settings().scheme)) {
    throw Error(fmt::format(
        "stage '{}': the grid model needs scheme velocity_verlet or nve (a Shardlow sweep "
        "moves the velocities outside the grid step)",
        stage));
  }
  DpdGridSettings s;
  s.cell_size = grid.cell_size;
  s.flip = grid.flip;
  s.move = grid.midpoint_move ? grid::PointMove::kMidpoint : grid::PointMove::kStepStart;
  for (const auto& m : motions) s.rigid.push_back({m.mask, m.velocity, m.free_body});
  try {
    return std::make_unique<DpdGridStep>(engine, s);
  } catch (const Error& e) {
    throw Error(fmt::format("stage '{}': {}", stage, e.what()));
  }
}

// The probes' columns sampled every sample_every steps, with the step,
// the time and the temperature after step 0.
class DpdProbeSeries {
 public:
  DpdProbeSeries(const std::vector<DpdProbeSpec>& specs, const DpdModel& model)
      : probes_(specs, model), samples_(probes_.columns().size()) {}

  // Collective: one sample; the thermo state holds the conservative
  // virial and energy when a probe or `with_potential` needs them.
  ThermoState sample(DpdEngine& engine, std::int64_t step, double dt, bool with_potential) {
    ThermoState thermo = engine.thermo(probes_.needs_potential() || with_potential);
    const auto values = probes_.sample(engine, thermo);
    for (std::size_t c = 0; c < values.size(); ++c) samples_[c].push_back(values[c]);
    step_.push_back(static_cast<double>(step));
    time_.push_back(static_cast<double>(step) * dt);
    if (step > 0) temperatures_.push_back(thermo.temperature);
    return thermo;
  }

  void report(StageResults& r) const {
    if (!temperatures_.empty()) {
      r.add_scalar("mean_temperature",
                   std::accumulate(temperatures_.begin(), temperatures_.end(), 0.0) /
                       static_cast<double>(temperatures_.size()),
                   "K");
    }
  }
  void save(CheckpointArchive& a) const {
    a.put("probes/step", step_);
    a.put("probes/time", time_);
    a.put("probes/temperatures", temperatures_);
    a.put("probes/references", probes_.references());
    for (std::size_t c = 0; c < samples_.size(); ++c) {
      a.put(fmt::format("probes/column_{}", c), samples_[c]);
    }
  }
  void load(const CheckpointArchive& a) {
    step_ = a.get("probes/step");
    time_ = a.get("probes/time");
    temperatures_ = a.get("probes/temperatures");
    probes_.set_references(a.get("probes/references"));
    for (std::size_t c = 0; c < samples_.size(); ++c) {
      samples_[c] = a.get(fmt::format("probes/column_{}", c));
    }
  }
  void report_table(StageResults& r) const {
    r.add_column("probes", "step", "1", step_);
    r.add_column("probes", "time", "ps", time_);
    for (std::size_t c = 0; c < samples_.size(); ++c) {
      r.add_column("probes", probes_.columns()[c], probes_.units()[c], samples_[c]);
    }
  }

 private:
  DpdProbes probes_;
  std::vector<std::vector<double>> samples_;
  std::vector<double> step_, time_, temperatures_;
};

// The engine and everything a stage observes of it, stepped together.
struct DpdRun {
  const DpdRunParams& params;
  DpdEngine& engine;
  DpdGridStep* grid_step;  // null: velocity Verlet or Shardlow without a grid
  const std::vector<DpdModel::GroupMotion>& group_motions;
  DpdProbeSeries& probes;
  DpdTrajectory& trajectory;
  DpdImpactAnalysis* impact;
  DpdTensionAnalysis* tension;
  std::vector<NeckProbe>& necks;

  [[nodiscard]] double dt() const { return engine.settings().dt; }

  ThermoState sample(std::int64_t step) {
    const ThermoState thermo = probes.sample(engine, step, dt(), tension != nullptr);
    const double t = static_cast<double>(step) * dt();
    if (tension) tension->sample(engine, thermo, t);
    if (!necks.empty()) {
      DpdView view;
      const auto now = view.view(engine);
      for (auto& neck : necks) neck.sample(t, now);
    }
    return thermo;
  }
  // Grips on a velocity ramp take each step's speed before it.
  void ramp_grips(std::int64_t n) {
    for (const auto& r : ramped_velocities(group_motions, n, dt())) {
      if (grid_step) {
        grid_step->set_rigid_velocity(r.mask, r.velocity);
      } else {
        engine.set_group_velocity(r.mask, r.velocity);
      }
    }
  }
  // Everything the run needs to go on after `step`, with the energies
  // energy_drift is measured from.
  CheckpointArchive save(const ThermoState& initial) const {
    CheckpointArchive a;
    put_engine_state(a, engine, grid_step);
    a.put("run/initial_energies",
          std::vector<double>{initial.kinetic, initial.potential, initial.internal});
    probes.save(a);
    if (impact) impact->save(a);
    if (tension) tension->save(a);
    for (const auto& neck : necks) neck.save(a);
    return a;
  }
  // The state `save` wrote; returns the step it was written after and sets
  // `initial`.
  std::int64_t load(const CheckpointArchive& a, ThermoState& initial) {
    const std::int64_t step = take_engine_state(a, engine, grid_step);
    const auto& e = a.get("run/initial_energies");
    initial.kinetic = e.at(0);
    initial.potential = e.at(1);
    initial.internal = e.at(2);
    probes.load(a);
    if (impact) impact->load(a);
    if (tension) tension->load(a);
    for (auto& neck : necks) neck.load(a);
    return step;
  }
  void step(std::int64_t n) {
    set_current_step(n);
    ramp_grips(n);
    if (grid_step) {
      grid_step->step();
    } else {
      engine.step();
    }
    if (params.mode == Mode::kEquilibrate) engine.berendsen(params.target_temperature, params.tau);
    if (impact) impact->track(engine, n, dt());
  }
};

void report_run(StageResults& r, const DpdEngine& engine, const DpdProbeSeries& probes,
                const ThermoState& initial, const ThermoState& last, std::int64_t steps,
                double seconds, std::int64_t steps_timed) {
  r.add_scalar("steps", static_cast<double>(steps), "1");
  r.add_scalar("particles", static_cast<double>(engine.total_particles()), "1");
  r.add_scalar("temperature", last.temperature, "K");
  probes.report(r);
  r.add_scalar("potential_energy", last.potential, "eV");
  r.add_scalar("total_energy", last.total(), "eV");
  r.add_scalar("energy_drift",
               (last.total() - initial.total()) / std::max(std::abs(initial.total()), 1e-300), "1");
  r.add_scalar("pressure", (last.pressure[0] + last.pressure[1] + last.pressure[2]) / 3.0, "bar");
  if (steps_timed > 0 && seconds > 0.0) {
    r.add_scalar("steps_per_second", static_cast<double>(steps_timed) / seconds, "1/s");
  }
  probes.report_table(r);
}

// A baseline is subtracted sample by sample (analysis::baseline_covers).
void check_baseline(const ImpactParams& impact, std::int64_t steps, double dt,
                    const std::string& stage) {
  if (!impact.baseline) return;
  const std::vector<double>& t = impact.baseline->time;
  if (!analysis::baseline_covers(t, steps, dt)) {
    throw Error(fmt::format(
        "stage '{}': impact.baseline has {} samples {} ps apart; this stage takes {} of {} ps: "
        "run the baseline at least as long, with the same dt",
        stage, t.size(), t.size() > 1 ? t[1] - t[0] : 0.0, steps + 1, dt));
  }
}

void run_stage(StageContext& ctx, const DpdRunParams& rp) {
  const DpdStageParams& p = rp.stage;
  use_run_directory(ctx.run_dir());
  const MesoparticleMaterial material = MesoparticleMaterial::from_yaml(ctx.material(p.material));
  DpdModel model = build_dpd_model(
      p, material, stage_seed(ctx.seed(), rp.noise_of.value_or(ctx.stage())), ctx.stage());
  std::optional<DpdTensionAnalysis> tension;
  if (rp.tension) tension.emplace(*rp.tension, model, material);
  DpdEngine engine(ctx.comm(), model.box, std::move(model.pair), model.settings,
                   std::move(model.particles));
  engine.set_prescribed_groups(model.prescribed_mask);
  engine.set_rigid_bodies(model.rigid_bodies);
  std::unique_ptr<DpdGridStep> grid_step;
  if (p.grid) grid_step = make_grid_step(engine, *p.grid, model.group_motions, ctx.stage());

  DpdProbeSeries probes(p.probes, model);
  std::optional<DpdImpactAnalysis> impact;
  if (rp.mode == Mode::kImpact) {
    if (!rp.impact) throw Error(fmt::format("stage '{}': mode impact needs `impact`", ctx.stage()));
    check_baseline(*rp.impact, p.steps, engine.settings().dt, ctx.stage());
    impact.emplace(*rp.impact, model, engine);
  }
  if (rp.mode == Mode::kTension) {
    if (!tension) throw Error(fmt::format("stage '{}': mode tension needs `tension`", ctx.stage()));
    tension->start(engine);
  }
  DpdTrajectory trajectory(ctx.comm(), ctx.stage_dir() / "particles.h5md", p.write_forces,
                           p.write_internal_energy);
  std::vector<NeckProbe> necks;
  for (const auto& n : rp.necks) {
    necks.emplace_back(ctx.comm(), n, model.group_mask(n.first), model.group_mask(n.second),
                       material.lattice_constant);
  }
  DpdRun run{rp,
             engine,
             grid_step.get(),
             model.group_motions,
             probes,
             trajectory,
             impact ? &*impact : nullptr,
             tension ? &*tension : nullptr,
             necks};

  StageCheckpoints checkpoints(ctx);
  ThermoState initial;
  std::int64_t first_step = 1;
  if (checkpoints.enabled() && checkpoints.resuming()) {
    first_step = run.load(checkpoints.resume_archive(), initial) + 1;
    trajectory.resume(engine, first_step - 1);
  } else {
    const ThermoState first = run.sample(0);
    initial = first.potential != 0.0 ? first : engine.thermo(true);
    if (impact) impact->track(engine, 0, run.dt());
    if (p.particles_every > 0 || p.steps == 0) trajectory.write_frame(engine, 0, run.dt());
  }
  const auto started = std::chrono::steady_clock::now();
  for (std::int64_t n = first_step; n <= p.steps; ++n) {
    run.step(n);
    if (n % p.sample_every == 0 || n == p.steps) run.sample(n);
    if ((p.particles_every > 0 && n % p.particles_every == 0) || n == p.steps) {
      trajectory.write_frame(engine, n, run.dt());
    }
    const bool stop = checkpoints.stop_agreed(n) && n < p.steps;
    if (stop || checkpoints.due(n, p.steps)) {
      const std::string file = checkpoints.write(n, static_cast<double>(n) * run.dt(),
                                                 [&] { return run.save(initial); });
      if (stop) throw StageFailure(StageCheckpoints::stopped_message(n, p.steps, file));
    }
    ctx.progress(n, p.steps, static_cast<double>(n) * run.dt(), "dpd");
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const ThermoState last = engine.thermo(true);
  trajectory.keep_final_state(engine, ctx.stage());

  auto& r = ctx.results();
  report_run(r, engine, probes, initial, last, p.steps, seconds, p.steps - first_step + 1);
  if (impact) impact->report(r);
  if (tension && rp.mode == Mode::kTension) tension->report(r, ctx.stage());
  for (const auto& neck : necks) neck.report(r, rp.neck_stable_time);
  checkpoints.report(r);
  r.attributes["decomposition"] = fmt::format("{}x{}x{}", engine.domain().dims()[0],
                                              engine.domain().dims()[1], engine.domain().dims()[2]);
  r.attributes["neighbour_list_builds"] = fmt::format("{}", engine.rebuilds());
  if (grid_step) {
    r.attributes["grid_cell_size"] = fmt::format("{:g}", grid_step->grid().cell_size());
  }
  if (trajectory.written() && ctx.rank() == 0) {
    r.files.push_back((std::filesystem::path(ctx.stage()) / "particles.h5md").string());
  }
}

}  // namespace

void DpdRunStage::run(StageContext& ctx) {
  run_stage(ctx, DpdRunParams::from_yaml(ctx.params()));
}

void DpdEquilibrateStage::run(StageContext& ctx) {
  run_stage(ctx, DpdRunParams::equilibrate_from_yaml(ctx.params()));
}

}  // namespace pbms::dpd
