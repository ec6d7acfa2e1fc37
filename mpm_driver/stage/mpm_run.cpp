#include "mpm_run.hpp"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include "bar_wave_analysis.hpp"
#include "engine/mpm_engine.hpp"
#include "mpm_model.hpp"
#include "mpm_output.hpp"
#include "mpm_run_params.hpp"
#include "probe_series.hpp"
#include "rod_tension_analysis.hpp"

#include "engine_checkpoint.hpp"
#include "pbms/driver/stage_checkpoints.hpp"

namespace pbms::mpm {
namespace {

// The materials the bodies use, in order of first use, in solver units.
MaterialSet body_materials(StageContext& ctx, const std::vector<BodyParams>& bodies,
                           bool metal_units) {
  std::vector<std::string> names;
  std::vector<YAML::Node> entries;
  for (const auto& b : bodies) {
    if (std::find(names.begin(), names.end(), b.material) != names.end()) continue;
    names.push_back(b.material);
    entries.push_back(ctx.material(b.material));
  }
  return materials_from_yaml(names, entries, metal_units);
}

}  // namespace

void MpmRunStage::run(StageContext& ctx) {
  const MpmRunParams params = MpmRunParams::from_yaml(ctx.params());
  MaterialSet materials = body_materials(ctx, params.model.bodies, params.metal_units);
  MpmModel model = build_model(params.model, materials);
  MpmEngine engine(ctx.comm(), std::move(model), std::move(materials));

  const double dt =
      params.time_step_for(engine.stable_time_step(), engine.model().grid.cell_size(), ctx.stage());
  const std::int64_t steps = params.steps(dt);
  ProbeSeries probes(params.probes, engine.model(), params.metal_units);
  std::optional<BarWaveAnalysis> bar;
  if (params.wave_front) bar.emplace(*params.wave_front, engine, dt, steps, ctx.stage());
  std::optional<RodTensionAnalysis> tension;
  if (params.tension) tension.emplace(*params.tension, engine, params.metal_units, ctx.stage());
  StageCheckpoints checkpoints(ctx);
  const bool resuming = checkpoints.enabled() && checkpoints.resuming();
  MpmOutput output(engine, params, ctx.stage_dir(), ctx.stage(), resuming);

  const auto save = [&] {
    CheckpointArchive a;
    put_engine_state(a, engine);
    probes.save(a);
    if (bar) bar->save(a);
    if (tension) tension->save(a);
    return a;
  };
  // A run of 0 steps still samples and writes the initial state.
  const auto sample = [&](std::int64_t n, double t) {
    probes.sample(engine, n, t);
    if (bar) bar->sample(engine, t);
    if (tension) tension->sample(engine, t);
  };
  std::int64_t first_step = 1;
  if (resuming) {
    const CheckpointArchive a = checkpoints.resume_archive();
    const std::int64_t step = take_engine_state(a, engine);
    probes.load(a);
    if (bar) bar->load(a);
    if (tension) tension->load(a);
    output.resume(engine, step);
    first_step = step + 1;
  } else {
    sample(0, 0.0);
    output.write(engine, 0, 0.0);
  }
  for (std::int64_t n = first_step; n <= steps; ++n) {
    ramp_point_velocities(engine.model(), engine.boundary_conditions(), n, dt);
    engine.step(dt);
    const double t = static_cast<double>(n) * dt;
    if (n % params.sample_every == 0 || n == steps) sample(n, t);
    output.write(engine, n, t);
    if (bar) bar->after_step(engine, n, t);
    const bool stop = checkpoints.stop_agreed(n) && n < steps;
    if (stop || checkpoints.due(n, steps)) {
      const std::string file = checkpoints.write(n, t, save);
      if (stop) throw StageFailure(StageCheckpoints::stopped_message(n, steps, file));
    }
    ctx.progress(n, steps, t, "mpm");
  }

  auto& r = ctx.results();
  r.add_scalar("steps", static_cast<double>(steps), "1");
  r.add_scalar("time_step", dt, params.time_unit());
  r.add_scalar("particles", static_cast<double>(engine.total_points()), "1");
  probes.report(r, params, ctx.stage());
  if (bar) bar->report(r, params.metal_units, ctx.stage());
  if (tension) tension->report(r, ctx.stage());
  checkpoints.report(r);
  r.attributes["gradient"] = params.gradient;
  const auto& dims = engine.partition().dims();
  r.attributes["decomposition"] = fmt::format("{}x{}x{}", dims[0], dims[1], dims[2]);
  for (auto& f : output.files()) r.files.push_back(std::move(f));
}

}  // namespace pbms::mpm
