#include "md_tension.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "md_setup.hpp"
#include "pbms/analysis/block_average.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"
#include "tension_checkpoints.hpp"

namespace pbms::md {

using config::OutputSpec;
using config::Param;
using units::Dimension;

config::StageKindSpec TensionStage::spec() {
  config::StageKindSpec s;
  s.kind = "md_tension";
  s.program = "md_driver";
  s.doc =
      "Uniaxial tension along x at a constant strain rate: a nanowire with free surfaces "
      "pulled by rigid grips (Nose-Hoover NVT), or a crystal periodic in x, y, z stretched "
      "by its box with y and z held at zero stress (Nose-Hoover NPT on y, z)";
  s.material_kinds = {"eam_alloy", "eam_fs", "sutton_chen"};
  s.cacheable = true;
  s.checkpoints = true;
  s.params = {
      Param::identifier("material", "Material to simulate").require().material(),
      Param::choice("lateral", {"free", "periodic"},
                    "free: a nanowire with free surfaces, pulled by grips; periodic: a bulk "
                    "crystal, periodic in all directions, laterally stress free")
          .def(std::string("free")),
      Param::int_list("cells", "Crystal size in unit cells (length x, cross-section y, z)")
          .def(std::vector<int>{40, 10, 10})
          .length(3, 3)
          .at_least(2),
      Param::real("lattice_constant", Dimension::kLength,
                  "Lattice constant at the test temperature; defaults to the material's")
          .above(0)
          .referable(),
      Param::real("temperature", Dimension::kTemperature, "Temperature").def(300.0).above(0),
      Param::real("strain_rate", Dimension::kRate,
                  "Engineering strain rate of the gauge (free) or of the box (periodic)")
          .def(1.0e-3)
          .above(0),
      Param::real("initial_strain", Dimension::kNone,
                  "periodic only: strain of the box during equilibration, where loading starts; "
                  "negative (compression) centres the fit window on zero strain")
          .def(0.0)
          .at_least(-0.05)
          .at_most(0.0)
          .only_when("lateral", "periodic"),
      Param::real("max_strain", Dimension::kNone, "Strain at which the test stops")
          .def(0.1)
          .above(0)
          .at_most(2.0),
      Param::real("fit_max_strain", Dimension::kNone,
                  "Young's modulus is fitted to strains up to this value")
          .def(0.02)
          .above(0),
      Param::integer("grip_cells", "free only: thickness of each rigid grip in unit cells")
          .def(2)
          .at_least(1),
      Param::choice("wire_start", {"profile", "rest"},
                    "free only: how the wire between the grips starts the pull. profile: "
                    "moving with the grips' linear velocity profile, so no wave is launched; "
                    "rest: at rest, the grips at full speed, launching a stress wave from each "
                    "(the gauge's early stress then carries the wave: docs/md-driver.md)")
          .def(std::string("profile"))
          .only_when("lateral", "free"),
      Param::real("timestep", Dimension::kTime, "MD time step").def(0.002).above(0).at_most(0.01),
      Param::real("equilibration", Dimension::kTime, "Time at temperature before loading")
          .def(10.0)
          .at_least(0),
      Param::integer("sample_every", "Steps between stress samples").def(50).above(0),
      Param::integer("trajectory_every", "Steps between H5MD frames; 0 writes none")
          .def(0)
          .at_least(0),
  };
  s.outputs = {
      {"youngs_modulus", OutputSpec::Shape::kScalar, "GPa",
       "Slope of the axial stress (the gauge's virial stress, or the periodic box's) vs "
       "strain up to fit_max_strain; its error from blocks of residuals when periodic"},
      {"youngs_modulus_grip_force", OutputSpec::Shape::kScalar, "GPa",
       "free: the same slope from the grip forces over the initial cross-section"},
      {"lateral_stress", OutputSpec::Shape::kScalar, "GPa",
       "periodic: mean of the y and z stresses over the fit window (zero if laterally free)"},
      {"ultimate_stress", OutputSpec::Shape::kScalar, "GPa", "Largest stress reached"},
      {"strain_at_ultimate", OutputSpec::Shape::kScalar, "1", "Strain at the largest stress"},
      {"stress_strain", OutputSpec::Shape::kTable, "",
       "Strain, axial stress, then the grip-force stress (free) or the y and z stresses "
       "(periodic), and temperature"},
  };
  return s;
}

namespace {

// The stage's parameters (schema and defaults: spec() above), with the
// step counts they give; times in ps, rates in 1/ps, lengths in Å.
struct TensionParams {
  std::string material;
  bool periodic = false;
  std::array<int, 3> cells{};
  std::optional<double> lattice_constant;  // empty: the material's
  double temperature = 0, rate = 0, initial_strain = 0, max_strain = 0, fit_max = 0;
  double dt = 0;
  int grip = 0;
  bool wire_at_rest = false;  // wire_start: rest
  int64_t n_equil = 0, n_load = 0, every = 0, traj_every = 0;

  static TensionParams from_yaml(const YAML::Node& p);
  // Throws pbms::Error naming the stage for grips that leave no wire, which
  // only the cell count reveals, and for initial_strain with lateral: free,
  // which the schema refuses already (only_when) but a driver called
  // without the coupler's validation could be given.
  void check(const std::string& stage) const;
  [[nodiscard]] double lattice_constant_of(const MdMaterial& mat) const {
    return lattice_constant.value_or(mat.lattice_constant);
  }
};

TensionParams TensionParams::from_yaml(const YAML::Node& p) {
  TensionParams s;
  s.material = p["material"].as<std::string>();
  s.periodic = p["lateral"].as<std::string>() == "periodic";
  s.cells = cells_of(p["cells"]);
  if (p["lattice_constant"]) s.lattice_constant = p["lattice_constant"].as<double>();
  s.temperature = p["temperature"].as<double>();
  s.rate = p["strain_rate"].as<double>();
  s.initial_strain = p["initial_strain"].as<double>();
  s.max_strain = p["max_strain"].as<double>();
  s.fit_max = p["fit_max_strain"].as<double>();
  s.grip = p["grip_cells"].as<int>();
  s.wire_at_rest = p["wire_start"] && p["wire_start"].as<std::string>() == "rest";
  s.dt = p["timestep"].as<double>();
  s.n_equil = steps_for(p["equilibration"].as<double>(), s.dt);
  s.n_load = steps_for((s.max_strain - s.initial_strain) / s.rate, s.dt);
  s.every = p["sample_every"].as<int64_t>();
  s.traj_every = p["trajectory_every"].as<int64_t>();
  return s;
}

void TensionParams::check(const std::string& stage) const {
  if (!periodic && initial_strain != 0.0) {
    throw Error(
        fmt::format("stage '{}': initial_strain applies to lateral: periodic only; a "
                    "nanowire starts unstrained",
                    stage));
  }
  if (!periodic && 2 * grip >= cells[0] - 1) {
    throw Error(fmt::format("stage '{}': grips of {} cells leave no wire between them in {} cells",
                            stage, grip, cells[0]));
  }
}

// Steps a phase of the stage (equilibration, then loading, each a LAMMPS
// run from its step 0) to its end, from where a resumed stage stands in
// it; writes frames, reports progress with `label(done)` and writes
// checkpoints. Chunks fall on sample boundaries, where a checkpoint cuts
// no averaging window.
void run_phase(StageContext& ctx, Lammps& lmp, TrajectoryRecorder& traj, TensionCheckpoints& ck,
               const TensionParams& s, bool loading,
               const std::function<std::string(int64_t)>& label) {
  const int64_t total = s.n_equil + s.n_load;
  const int64_t offset = loading ? s.n_equil : 0, steps = loading ? s.n_load : s.n_equil;
  const int64_t align = std::lcm(std::max<int64_t>(1, s.traj_every), s.every);
  // LAMMPS' step counter where the phase began (a minimisation advances it).
  const auto begin =
      static_cast<int64_t>(lmp.thermo("step")) - (ck.resumes_in(loading) ? ck.resumed()->step : 0);
  if (ck.resumes_in(loading)) ck.adopt_script();
  lmp.run_rest(begin, begin + steps, chunk_for(total, align), [&](int64_t done) {
    traj.maybe_write(offset + done, (offset + done) * s.dt);
    ctx.progress(offset + done, total, (offset + done) * s.dt, label(done));
    ck.after_chunk(loading, done, offset + done, total, s.dt);
  });
}

// The relaxed wire's grips, end slabs moved rigidly at +/- speed.
struct Grips {
  double xlo = 0, xhi = 0, length = 0;  // wire ends and grip thickness
  double gauge = 0;                     // initial length between the grips
  double speed = 0;
  [[nodiscard]] std::vector<double> values() const { return {xlo, xhi, length, gauge, speed}; }
  static Grips of(const std::vector<double>& v) {
    return {v.at(0), v.at(1), v.at(2), v.at(3), v.at(4)};
  }
};

// The fixes that hold the grips rigid and thermostat the wire between
// them: what a resumed loading sets again (the groups and the
// thermostat's state come with the restart file). The wire's thermostat
// is not `nvt`, the equilibration's: LAMMPS would hand it that one's
// state from a restart file written during equilibration.
void hold_grips(Lammps& lmp, const TensionParams& s) {
  lmp.command("fix hold_left left setforce 0 0 0");
  lmp.command("fix hold_right right setforce 0 0 0");
  lmp.command("fix move_grips grips nve");
  lmp.command(fmt::format("fix wire_nvt wire nvt temp {0} {0} 0.1", s.temperature));
  lmp.command("compute wire_temp wire temp");
}

// Holds the end slabs of the relaxed wire rigid and sets them moving apart,
// the wire between them thermostatted.
Grips attach_grips(Lammps& lmp, const TensionParams& s, double a) {
  lmp.command("variable xlo equal bound(all,xmin)");
  lmp.command("variable xhi equal bound(all,xmax)");
  Grips g;
  g.xlo = lmp.variable("xlo");
  g.xhi = lmp.variable("xhi");
  g.length = s.grip * a;
  g.gauge = g.xhi - g.xlo - 2.0 * g.length;
  g.speed = 0.5 * s.rate * g.gauge;
  lmp.command(fmt::format("region left_grip block INF {:.10g} INF INF INF INF units box",
                          g.xlo + g.length));
  lmp.command(fmt::format("region right_grip block {:.10g} INF INF INF INF INF units box",
                          g.xhi - g.length));
  lmp.command("group left region left_grip");
  lmp.command("group right region right_grip");
  lmp.command("group grips union left right");
  lmp.command("group wire subtract all grips");
  hold_grips(lmp, s);
  lmp.command("reset_timestep 0");
  lmp.command(fmt::format("velocity left set {} 0 0 units box", -g.speed));
  lmp.command(fmt::format("velocity right set {} 0 0 units box", g.speed));
  // The wire starts from the matching linear velocity profile, so no shock
  // is launched from the grips (unless it is asked to start at rest).
  if (!s.wire_at_rest) {
    lmp.command(fmt::format("velocity wire ramp vx {} {} x {:.10g} {:.10g} sum yes units box",
                            -g.speed, g.speed, g.xlo + g.length, g.xhi - g.length));
  }
  return g;
}

// Samples of the wire every `every` steps: (strain, virial stress,
// grip-force stress, wire temperature), also printed in full precision.
void sample_wire(Lammps& lmp, const TensionParams& s, const Grips& g, double area) {
  const int64_t every = s.every;
  // Two measures of the axial stress, each averaged over a sampling window:
  // the virial stress of the gauge atoms (as the seed computes it), and the
  // force the wire exerts on the grips (read before setforce zeroes it) over
  // the initial cross-section. The first is far less noisy; both must agree.
  const double to_gpa = 1.0 / units::kBarPerGPa;
  lmp.command("compute atom_stress wire stress/atom NULL");
  lmp.command("compute wire_sxx wire reduce sum c_atom_stress[1]");
  lmp.command(
      fmt::format("variable gauge_length equal {:.12g}+{:.12g}*step*dt", g.gauge, 2.0 * g.speed));
  lmp.command(fmt::format("variable virial_stress equal c_wire_sxx/({:.12g}*v_gauge_length)*{}",
                          area, to_gpa));
  lmp.command(
      fmt::format("variable grip_stress equal (f_hold_left[1]-f_hold_right[1])/(2*{:.12g})*{:.12g}",
                  area, units::kBarPerEvPerA3 * to_gpa));
  lmp.command(
      fmt::format("fix stress_avg all ave/time 1 {0} {0} v_virial_stress v_grip_stress", every));
  // Strain at the middle of the window the stress was averaged over.
  lmp.command(
      fmt::format("variable strain equal (step-{:.1f})*dt*{:.12g}", 0.5 * (every - 1), s.rate));
  lmp.command("variable virial_avg equal f_stress_avg[1]");
  lmp.command("variable grip_avg equal f_stress_avg[2]");
  lmp.command("variable wire_temp equal c_wire_temp");
  lmp.command(
      fmt::format("fix samples all vector {} v_strain v_virial_avg v_grip_avg v_wire_temp", every));
  // The same samples in the log in full precision, so that a plain `lmp -in`
  // of the script can be compared with the stress-strain table row by row.
  lmp.command(fmt::format(
      "fix print_samples all print {} \"PBMS_SAMPLE $(step) $(v_strain) $(v_virial_avg) "
      "$(v_grip_avg) $(v_wire_temp)\" screen yes",
      every));
}

// The nanowire: rows of (strain, virial stress, grip-force stress, wire
// temperature), one per sample, the first at step 0.
std::vector<std::vector<double>> pull_nanowire(StageContext& ctx, Lammps& lmp,
                                               const TensionParams& s, const MdMaterial& mat,
                                               TensionCheckpoints& ck) {
  const double a = s.lattice_constant_of(mat), temperature = s.temperature, rate = s.rate,
               dt = s.dt;
  const double area = s.cells[1] * a * s.cells[2] * a;
  const auto& from = ck.resume(mat);
  if (!from) {
    build_crystal(lmp, mat, a, s.cells, "s s s");
    lmp.command(fmt::format("timestep {}", dt));
    // Relax the surfaces at 0 K first: a thin wire cut from bulk contracts
    // by ~1 %, and doing that in MD would leave it ringing axially for many
    // ps.
    lmp.command("minimize 0 1e-8 1000 10000");
    // The wire then equilibrates free: surface stress shortens a thin wire,
    // and holding its ends at the bulk spacing would pre-stress it by GPa.
    lmp.command(fmt::format("velocity all create {} {} mom yes rot yes dist gaussian",
                            2.0 * temperature, lammps_seed(ctx.seed(), 7)));
  } else {
    lmp.command(fmt::format("timestep {}", dt));
  }
  const bool equilibrating = !from || !from->loading;
  if (equilibrating) {
    lmp.command(fmt::format("fix nvt all nvt temp {0} {0} 0.1", temperature));
    lmp.command("fix no_drift all momentum 100 linear 1 1 1 angular");
  }
  lmp.command("thermo_style custom step temp pe lx");
  lmp.command("thermo 1000");
  TrajectoryRecorder traj(ctx, lmp, "tension.h5md", s.traj_every, {false, false, false},
                          from ? (from->loading ? s.n_equil : 0) + from->step : -1);
  if (!from) traj.maybe_write(0, 0.0);
  Grips grips;
  if (equilibrating) {
    run_phase(ctx, lmp, traj, ck, s, false, [](int64_t) { return "equilibration"; });
    lmp.command("unfix nvt");
    lmp.command("unfix no_drift");
    grips = attach_grips(lmp, s, a);
  } else {
    grips = Grips::of(from->grips);
    hold_grips(lmp, s);
  }
  ck.set_grips(grips.values());
  sample_wire(lmp, s, grips, area);
  run_phase(ctx, lmp, traj, ck, s, true,
            [&](int64_t done) { return fmt::format("strain {:.4f}", done * dt * rate); });
  if (ctx.rank() == 0 && traj.enabled()) ctx.results().files.push_back(traj.relative_path());
  return ck.samples();
}

// Samples of the periodic box every `every` steps: strain lx/l0 - 1 and the
// stresses from the pressure tensor (tension positive, GPa), each averaged
// over the window, and the temperature; also printed in full precision for
// the plain `lmp -in` comparison.
void sample_box(Lammps& lmp, double l0, int64_t every) {
  const double to_gpa = 1.0 / units::kBarPerGPa;
  lmp.command(fmt::format("variable strain equal lx/{:.15g}-1", l0));
  for (const char* c : {"xx", "yy", "zz"}) {
    lmp.command(fmt::format("variable s{0} equal -p{0}*{1}", c, to_gpa));
  }
  lmp.command(
      fmt::format("fix stress_avg all ave/time 1 {0} {0} v_strain v_sxx v_syy v_szz", every));
  const char* names[] = {"strain_avg", "sxx_avg", "syy_avg", "szz_avg"};
  for (int i = 0; i < 4; ++i) {
    lmp.command(fmt::format("variable {} equal f_stress_avg[{}]", names[i], i + 1));
  }
  lmp.command("variable temp_now equal temp");
  lmp.command(fmt::format(
      "fix samples all vector {} v_strain_avg v_sxx_avg v_syy_avg v_szz_avg v_temp_now", every));
  lmp.command(fmt::format(
      "fix print_samples all print {} \"PBMS_SAMPLE $(step) $(v_strain_avg) $(v_sxx_avg) "
      "$(v_syy_avg) $(v_szz_avg) $(v_temp_now)\" screen yes",
      every));
}

// The periodic crystal: rows of (strain, stress xx, yy, zz, temperature).
std::vector<std::vector<double>> pull_periodic(StageContext& ctx, Lammps& lmp,
                                               const TensionParams& s, const MdMaterial& mat,
                                               TensionCheckpoints& ck) {
  const double a = s.lattice_constant_of(mat);
  // Strain is measured against the crystal at `lattice_constant`, which is
  // stress free at the temperature when that is the isotherm's zero-pressure
  // value; a small error in it shifts the curve, not its slope.
  const double l0 = s.cells[0] * a;
  const auto& from = ck.resume(mat);
  if (!from) {
    build_crystal(lmp, mat, a, s.cells, "p p p");
    if (s.initial_strain != 0.0) {
      lmp.command(fmt::format("change_box all x scale {:.15g} remap", 1.0 + s.initial_strain));
    }
    lmp.command(fmt::format("velocity all create {} {} mom yes rot yes dist gaussian",
                            2.0 * s.temperature, lammps_seed(ctx.seed(), 7)));
  }
  lmp.command(fmt::format("timestep {}", s.dt));
  // Nose-Hoover NPT on y and z alone (uncoupled, zero target stress) while x
  // is held, then stretched by fix deform. One fix from equilibration
  // through loading, so the barostat starts the ramp settled; a Berendsen
  // barostat beside fix nvt would add a second coupling for no gain. With
  // md_isotherm's 1 ps damping it follows ramps up to 0.4 %/ps: the lateral
  // stress then changes by < 0.03 GPa per unit strain (C12 ~ 120 GPa if held).
  lmp.command(fmt::format("fix npt all npt temp {0} {0} 0.1 y 0 0 1.0 z 0 0 1.0", s.temperature));
  lmp.command("thermo_style custom step temp pe lx ly lz pxx pyy pzz");
  lmp.command("thermo 1000");
  TrajectoryRecorder traj(ctx, lmp, "tension.h5md", s.traj_every, {true, true, true},
                          from ? (from->loading ? s.n_equil : 0) + from->step : -1);
  if (!from) traj.maybe_write(0, 0.0);
  if (!from || !from->loading) {
    run_phase(ctx, lmp, traj, ck, s, false, [](int64_t) { return "equilibration"; });
    lmp.command("reset_timestep 0");
  }
  // The box grows at the constant speed rate * l0: engineering strain rate
  // `rate` against the reference length. A resumed loading's fix deform
  // takes the box it started from out of the restart file.
  lmp.command(fmt::format("fix stretch all deform 1 x vel {:.15g} remap x units box", s.rate * l0));
  sample_box(lmp, l0, s.every);
  run_phase(ctx, lmp, traj, ck, s, true, [&](int64_t done) {
    return fmt::format("strain {:.4f}", s.initial_strain + done * s.dt * s.rate);
  });
  if (ctx.rank() == 0 && traj.enabled()) ctx.results().files.push_back(traj.relative_path());
  return ck.samples();
}

// Least-squares line through the samples up to fit_max. With `blocked`, the
// slope's standard error comes from 10 blocks of residuals, since
// consecutive stress samples are correlated (phonons, the thermostat and
// barostat); the residuals are about a parabola, since the curve bends
// (Mishin copper stiffens by ~300 GPa * strain^2 along [100]) and a line's
// residuals would count that bend as noise.
analysis::LineFit fit_elastic(const StageContext& ctx, const std::vector<double>& strain,
                              const std::vector<double>& y, double fit_max, bool blocked) {
  std::vector<double> fx, fy;
  for (size_t i = 0; i < strain.size(); ++i) {
    if (strain[i] <= fit_max) {
      fx.push_back(strain[i]);
      fy.push_back(y[i]);
    }
  }
  if (fx.size() < 3) {
    throw Error(
        fmt::format("stage '{}': only {} samples below fit_max_strain = {}; sample "
                    "more often or raise fit_max_strain",
                    ctx.stage(), fx.size(), fit_max));
  }
  auto fit = analysis::fit_line(fx, fy);
  if (blocked) {
    // Ten blocks of three samples at least, or the error would ignore the
    // correlated noise that the periodic crystal's stress carries.
    fit.slope_error = analysis::slope_block_error(fx, fy, 10);
    if (!std::isfinite(fit.slope_error)) {
      throw Error(
          fmt::format("stage '{}': {} samples below fit_max_strain = {}; the block error "
                      "of the modulus needs 30: sample more often",
                      ctx.stage(), fx.size(), fit_max));
    }
  }
  return fit;
}

void report(StageContext& ctx, const TensionParams& s, std::vector<std::vector<double>> rows) {
  // Row 0 is step 0, before any window was averaged.
  if (!rows.empty()) rows.erase(rows.begin());
  const auto strain = column(rows, 0), stress = column(rows, 1);
  auto& r = ctx.results();
  const auto fit = fit_elastic(ctx, strain, stress, s.fit_max, s.periodic);
  r.add_scalar("youngs_modulus", fit.slope, "GPa", fit.slope_error);
  r.add_column("stress_strain", "strain", "1", strain);
  r.add_column("stress_strain", "stress", "GPa", stress);
  if (s.periodic) {
    const auto syy = column(rows, 2), szz = column(rows, 3);
    std::vector<double> lateral;
    for (size_t i = 0; i < strain.size(); ++i) {
      if (strain[i] <= s.fit_max) lateral.push_back(0.5 * (syy[i] + szz[i]));
    }
    r.add_scalar("lateral_stress", analysis::mean(lateral), "GPa",
                 analysis::block_average(lateral, 10).error);
    r.add_column("stress_strain", "stress_yy", "GPa", syy);
    r.add_column("stress_strain", "stress_zz", "GPa", szz);
    r.add_column("stress_strain", "temperature", "K", column(rows, 4));
  } else {
    const auto grip_stress = column(rows, 2);
    const auto grip_fit = fit_elastic(ctx, strain, grip_stress, s.fit_max, false);
    r.add_scalar("youngs_modulus_grip_force", grip_fit.slope, "GPa", grip_fit.slope_error);
    r.add_column("stress_strain", "grip_stress", "GPa", grip_stress);
    r.add_column("stress_strain", "temperature", "K", column(rows, 3));
  }
  const auto peak = std::max_element(stress.begin(), stress.end()) - stress.begin();
  r.add_scalar("ultimate_stress", stress[static_cast<size_t>(peak)], "GPa");
  r.add_scalar("strain_at_ultimate", strain[static_cast<size_t>(peak)], "1");
  r.attributes["fit_min_strain"] = fmt::format("{}", strain.empty() ? 0.0 : strain.front());
  r.attributes["fit_max_strain"] = fmt::format("{}", s.fit_max);
  r.attributes["fit_intercept_gpa"] = fmt::format("{}", fit.intercept);
}

}  // namespace

void TensionStage::run(StageContext& ctx) {
  const TensionParams s = TensionParams::from_yaml(ctx.params());
  const MdMaterial mat = material_of(ctx, s.material);
  s.check(ctx.stage());
  StageCheckpoints checkpoints(ctx);
  std::optional<CheckpointArchive> from;
  if (checkpoints.enabled() && checkpoints.resuming()) from = checkpoints.resume_archive();
  // After each checkpoint the stage goes on from it in a new LAMMPS
  // instance, as a resumed stage does (tension_checkpoints.hpp).
  for (;;) {
    Lammps lmp(ctx.comm(), ctx.stage_dir() / "tension.log", from.has_value());
    lmp.comment(fmt::format("PBMS md_tension '{}' ({}): {}x{}x{} cells, {} K, strain rate {} 1/ps",
                            ctx.stage(), s.periodic ? "periodic" : "nanowire", s.cells[0],
                            s.cells[1], s.cells[2], s.temperature, s.rate));
    TensionCheckpoints ck(ctx, checkpoints, lmp, s.periodic ? 5 : 4, from ? &*from : nullptr);
    try {
      auto rows =
          s.periodic ? pull_periodic(ctx, lmp, s, mat, ck) : pull_nanowire(ctx, lmp, s, mat, ck);
      checkpoints.report(ctx.results());
      report(ctx, s, std::move(rows));
      if (ctx.rank() == 0) {
        lmp.write_script(ctx.stage_dir() / "tension.in", "md_tension " + ctx.stage());
        ctx.results().files.push_back(ctx.stage() + "/tension.in");
      }
      return;
    } catch (const ContinueFromCheckpoint& c) {
      from = CheckpointArchive::read(c.file, checkpoints.identity(), ctx.comm());
    }
  }
}

}  // namespace pbms::md
