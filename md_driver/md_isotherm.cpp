#include "md_isotherm.hpp"

#include <cmath>

#include <fmt/format.h>

#include "md_setup.hpp"
#include "pbms/analysis/block_average.hpp"
#include "pbms/analysis/equation_of_state.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/driver/stage_checkpoints.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::md {

using config::OutputSpec;
using config::Param;
using units::Dimension;

config::StageKindSpec IsothermStage::spec() {
  config::StageKindSpec s;
  s.kind = "md_isotherm";
  s.checkpoints = true;
  s.program = "md_driver";
  s.doc =
      "Pressure-volume isotherm of a periodic crystal by NPT MD (Nose-Hoover), with a "
      "Birch-Murnaghan fit";
  s.material_kinds = {"eam_alloy", "eam_fs", "sutton_chen"};
  s.cacheable = true;
  s.params = {
      Param::identifier("material", "Material to simulate").require().material(),
      Param::real("temperature", Dimension::kTemperature, "Temperature").def(298.0).above(0),
      Param::real_list("pressures", Dimension::kPressure,
                       "Pressure ladder; the fit needs at least 3 points")
          .def(std::vector<double>{0.0, 1.0e4, 2.0e4, 5.0e4, 1.0e5})
          .length(3, 100)
          .at_least(-1.0e5)
          .at_most(2.0e6),
      Param::int_list("cells", "Unit cells along x, y, z")
          .def(std::vector<int>{8, 8, 8})
          .length(3, 3)
          .at_least(2),
      Param::real("timestep", Dimension::kTime, "MD time step").def(0.002).above(0).at_most(0.01),
      Param::real("equilibration", Dimension::kTime, "NPT time before averaging, per pressure")
          .def(10.0)
          .at_least(0),
      Param::real("production", Dimension::kTime, "NPT time averaged, per pressure")
          .def(10.0)
          .above(0),
      Param::integer("sample_every", "Steps between samples of V and P").def(10).above(0),
      Param::real("thermostat_damping", Dimension::kTime, "Nose-Hoover temperature damping")
          .def(0.1)
          .above(0),
      Param::real("barostat_damping", Dimension::kTime, "Nose-Hoover pressure damping")
          .def(1.0)
          .above(0),
      Param::integer("trajectory_every", "Steps between H5MD frames; 0 writes none")
          .def(0)
          .at_least(0),
  };
  s.outputs = {
      {"lattice_parameter", OutputSpec::Shape::kScalar, "Å",
       "Mean lattice parameter at the pressure nearest zero (the lowest where none is "
       "negative): the crystal's own, which md_elastic and md_tension start from"},
      {"bulk_modulus", OutputSpec::Shape::kScalar, "GPa", "B0 of the Birch-Murnaghan fit"},
      {"bulk_modulus_derivative", OutputSpec::Shape::kScalar, "1", "B0' of the fit"},
      {"equilibrium_volume", OutputSpec::Shape::kScalar, "Å^3", "V0 per atom of the fit (P = 0)"},
      {"fit_rms_residual", OutputSpec::Shape::kScalar, "GPa", "RMS pressure misfit of the fit"},
      {"isotherm", OutputSpec::Shape::kTable, "",
       "Per pressure: target and mean pressure, volume per atom, V/V0, lattice parameter, "
       "temperature, with standard errors"},
  };
  return s;
}

namespace {

// The stage's parameters (schema and defaults: spec() above); times in ps,
// pressures in bar, temperatures in K.
struct IsothermParams {
  std::string material;
  double temperature = 0.0;
  std::vector<double> pressures;
  std::array<int, 3> cells{};
  double timestep = 0.0;
  double equilibration = 0.0;
  double production = 0.0;
  int64_t sample_every = 0;
  double thermostat_damping = 0.0;
  double barostat_damping = 0.0;
  int64_t trajectory_every = 0;

  static IsothermParams from_yaml(const YAML::Node& p);
};

IsothermParams IsothermParams::from_yaml(const YAML::Node& p) {
  IsothermParams r;
  r.material = p["material"].as<std::string>();
  r.temperature = p["temperature"].as<double>();
  r.pressures = p["pressures"].as<std::vector<double>>();
  r.cells = cells_of(p["cells"]);
  r.timestep = p["timestep"].as<double>();
  r.equilibration = p["equilibration"].as<double>();
  r.production = p["production"].as<double>();
  r.sample_every = p["sample_every"].as<int64_t>();
  r.thermostat_damping = p["thermostat_damping"].as<double>();
  r.barostat_damping = p["barostat_damping"].as<double>();
  r.trajectory_every = p["trajectory_every"].as<int64_t>();
  return r;
}

// What every point of the ladder shares: its step counts, the whole
// stage's for progress, and the atoms of the crystal.
struct Plan {
  int64_t n_equil = 0, n_prod = 0, per_point = 0, total = 0;
  double n_atoms = 0.0;
};

Plan plan_of(const StageContext& ctx, const IsothermParams& prm, const MdMaterial& mat) {
  Plan plan;
  const double dt = prm.timestep;
  plan.n_equil = steps_for(prm.equilibration, dt);
  plan.n_prod = steps_for(prm.production, dt);
  const int64_t every = prm.sample_every;
  if (plan.n_prod < 10 * every) {
    throw Error(
        fmt::format("stage '{}': production ({} steps) must span at least 10 samples "
                    "(sample_every = {})",
                    ctx.stage(), plan.n_prod, every));
  }
  plan.per_point = plan.n_equil + plan.n_prod;
  plan.total = plan.per_point * static_cast<int64_t>(prm.pressures.size());
  const double natoms_per_cell = mat.lattice == "fcc" ? 4.0 : 2.0;
  plan.n_atoms = natoms_per_cell * prm.cells[0] * prm.cells[1] * prm.cells[2];
  return plan;
}

// NPT at pressures[i]: equilibrates, then samples pressure, volume per atom,
// lattice parameter and temperature every sample_every steps of production.
// Returns the production samples; rank 0 writes the point's script.
std::vector<std::vector<double>> sample_point(StageContext& ctx, const IsothermParams& prm,
                                              const MdMaterial& mat, const Plan& plan, size_t i) {
  const auto& pressures = prm.pressures;
  const auto& cells = prm.cells;
  const double temperature = prm.temperature, dt = prm.timestep;
  const int64_t n_equil = plan.n_equil, n_prod = plan.n_prod, total = plan.total;
  const int64_t every = prm.sample_every, traj_every = prm.trajectory_every;
  const std::string tag = fmt::format("p{}", i);
  const std::string phase_label = fmt::format("P = {:.4g} GPa", pressures[i] / 1e4);
  Lammps lmp(ctx.comm(), ctx.stage_dir() / (tag + ".log"));
  lmp.comment(fmt::format("PBMS md_isotherm '{}', point {} of {}: {} K, {} bar", ctx.stage(), i + 1,
                          pressures.size(), temperature, pressures[i]));
  build_crystal(lmp, mat, mat.lattice_constant, cells, "p p p");
  lmp.command(fmt::format("timestep {}", dt));
  lmp.command(fmt::format("velocity all create {} {} mom yes rot yes dist gaussian",
                          2.0 * temperature, lammps_seed(ctx.seed(), i)));
  lmp.command(fmt::format("fix npt all npt temp {0} {0} {1} iso {2} {2} {3}", temperature,
                          prm.thermostat_damping, pressures[i], prm.barostat_damping));
  lmp.command("thermo 1000");
  lmp.command("thermo_style custom step temp press vol lx pe");
  TrajectoryRecorder traj(ctx, lmp, tag + ".h5md", traj_every, {true, true, true});
  const int64_t base = static_cast<int64_t>(i) * plan.per_point;
  auto report = [&](const char* phase, int64_t offset) {
    return [&, phase, offset](int64_t done) {
      const int64_t step = base + offset + done;
      traj.maybe_write(offset + done, (offset + done) * dt);
      ctx.progress(step, total, step * dt, fmt::format("{}: {}", phase_label, phase));
    };
  };
  traj.maybe_write(0, 0.0);
  if (n_equil > 0) lmp.run(n_equil, chunk_for(total, traj_every), report("equilibration", 0));
  // Averaging windows of fix ave/time are aligned to absolute step numbers.
  lmp.command("reset_timestep 0");
  lmp.command(fmt::format("variable alat equal lx/{}", cells[0]));
  lmp.command(fmt::format("variable vatom equal vol/{}", plan.n_atoms));
  lmp.command(
      fmt::format("fix samples all vector {} c_thermo_press v_vatom v_alat c_thermo_temp", every));
  lmp.command(fmt::format("fix means all ave/time {0} {1} {2} c_thermo_press v_vatom v_alat", every,
                          n_prod / every, n_prod / every * every));
  lmp.run(n_prod, chunk_for(total, traj_every), report("production", n_equil));
  // Replayed by a plain `lmp -in` this prints the same averages.
  lmp.command(
      "print \"PBMS_AVERAGES pressure $(f_means[1]) volume_per_atom $(f_means[2]) "
      "lattice_parameter $(f_means[3])\"");

  const auto rows = lmp.fix_array("samples", 4);
  if (ctx.rank() == 0) {
    lmp.write_script(
        ctx.stage_dir() / (tag + ".in"),
        fmt::format("md_isotherm point {}: T = {} K, P = {} bar", i, temperature, pressures[i]));
    ctx.results().files.push_back(ctx.stage() + "/" + tag + ".in");
    if (traj.enabled()) ctx.results().files.push_back(traj.relative_path());
  }
  // Drop the sample taken at the first production step (end of the
  // equilibration): only the production window is averaged.
  std::vector<std::vector<double>> prod(rows.begin() + (rows.size() > 1 ? 1 : 0), rows.end());
  return prod;
}

// The isotherm table: one row of means and standard errors per point.
struct Isotherm {
  std::vector<double> p_target, p_mean, p_err, vol, vol_err, alat, alat_err, temp;

  void add(double target, const std::vector<std::vector<double>>& prod) {
    const auto press = column(prod, 0), va = column(prod, 1), aa = column(prod, 2),
               tt = column(prod, 3);
    p_target.push_back(target);
    p_mean.push_back(analysis::mean(press));
    p_err.push_back(analysis::block_average(press, 10).error);
    vol.push_back(analysis::mean(va));
    vol_err.push_back(analysis::block_average(va, 10).error);
    alat.push_back(analysis::mean(aa));
    alat_err.push_back(analysis::block_average(aa, 10).error);
    temp.push_back(analysis::mean(tt));
  }
};

void report_isotherm(StageContext& ctx, const IsothermParams& prm, const MdMaterial& mat,
                     const Plan& plan, const Isotherm& t) {
  // Fit against the measured mean pressures: they, not the targets, belong
  // to the measured volumes.
  const auto fit = analysis::fit_birch_murnaghan(t.vol, t.p_mean);
  std::vector<double> ratio, ratio_err;
  for (size_t i = 0; i < t.vol.size(); ++i) {
    ratio.push_back(t.vol[i] / fit.v0);
    ratio_err.push_back(t.vol_err[i] / fit.v0);
  }
  const auto& pressures = prm.pressures;
  // Nearest zero rather than lowest: an isotherm that holds states in
  // tension (negative pressures, as a fit's target can) must not hand the
  // stretched crystal's lattice to the stages that want the crystal at rest.
  size_t nearest_zero = 0;
  for (size_t i = 1; i < pressures.size(); ++i) {
    if (std::abs(pressures[i]) < std::abs(pressures[nearest_zero])) nearest_zero = i;
  }
  auto& r = ctx.results();
  r.add_scalar("lattice_parameter", t.alat[nearest_zero], "Å", t.alat_err[nearest_zero]);
  r.add_scalar("bulk_modulus", fit.b0 / units::kBarPerGPa, "GPa");
  r.add_scalar("bulk_modulus_derivative", fit.b0_prime, "1");
  r.add_scalar("equilibrium_volume", fit.v0, "Å^3");
  r.add_scalar("fit_rms_residual", fit.rms_residual / units::kBarPerGPa, "GPa");
  r.add_column("isotherm", "pressure_target", "bar", t.p_target);
  r.add_column("isotherm", "pressure", "bar", t.p_mean);
  r.add_column("isotherm", "pressure_std_error", "bar", t.p_err);
  r.add_column("isotherm", "volume_per_atom", "Å^3", t.vol);
  r.add_column("isotherm", "volume_per_atom_std_error", "Å^3", t.vol_err);
  r.add_column("isotherm", "volume_ratio", "1", ratio);
  r.add_column("isotherm", "volume_ratio_std_error", "1", ratio_err);
  r.add_column("isotherm", "lattice_parameter", "Å", t.alat);
  r.add_column("isotherm", "lattice_parameter_std_error", "Å", t.alat_err);
  r.add_column("isotherm", "temperature", "K", t.temp);
  r.attributes["material"] = mat.name;
  r.attributes["potential"] = mat.potential;
  r.attributes["atoms"] = fmt::format("{}", static_cast<int64_t>(plan.n_atoms));
}

}  // namespace

namespace {

// The production samples of the points finished so far, for a checkpoint
// after each point: every point is its own LAMMPS run from its own seed, so
// a resumed isotherm runs the remaining points exactly as they would have
// run.
class FinishedPoints {
 public:
  void add(const std::vector<std::vector<double>>& prod) {
    std::vector<double> flat;
    for (const auto& row : prod) flat.insert(flat.end(), row.begin(), row.end());
    points_.push_back(std::move(flat));
  }
  [[nodiscard]] CheckpointArchive archive() const {
    CheckpointArchive a;
    a.put("isotherm/points", static_cast<double>(points_.size()));
    for (std::size_t k = 0; k < points_.size(); ++k) {
      a.put(fmt::format("isotherm/point_{}", k), points_[k]);
    }
    return a;
  }
  // The points a checkpoint holds, each as its production rows.
  static std::vector<std::vector<std::vector<double>>> read(const CheckpointArchive& a) {
    std::vector<std::vector<std::vector<double>>> out;
    const auto n = static_cast<std::size_t>(a.scalar("isotherm/points"));
    for (std::size_t k = 0; k < n; ++k) {
      const auto& flat = a.get(fmt::format("isotherm/point_{}", k));
      std::vector<std::vector<double>> rows;
      for (std::size_t r = 0; r + 4 <= flat.size(); r += 4) {
        rows.emplace_back(flat.begin() + static_cast<std::ptrdiff_t>(r),
                          flat.begin() + static_cast<std::ptrdiff_t>(r + 4));
      }
      out.push_back(std::move(rows));
    }
    return out;
  }

 private:
  std::vector<std::vector<double>> points_;
};

}  // namespace

void IsothermStage::run(StageContext& ctx) {
  const IsothermParams prm = IsothermParams::from_yaml(ctx.params());
  const MdMaterial mat = material_of(ctx, prm.material);
  const Plan plan = plan_of(ctx, prm, mat);
  const std::size_t n = prm.pressures.size();
  Isotherm table;
  FinishedPoints finished;
  StageCheckpoints checkpoints(ctx);
  std::size_t first = 0;
  if (checkpoints.enabled() && checkpoints.resuming()) {
    for (const auto& prod : FinishedPoints::read(checkpoints.resume_archive())) {
      const std::string tag = fmt::format("p{}", first);
      table.add(prm.pressures[first], prod);
      finished.add(prod);
      if (ctx.rank() == 0) {
        ctx.results().files.push_back(ctx.stage() + "/" + tag + ".in");
        if (prm.trajectory_every > 0)
          ctx.results().files.push_back(ctx.stage() + "/" + tag + ".h5md");
      }
      ++first;
    }
  }
  for (std::size_t i = first; i < n; ++i) {
    const auto prod = sample_point(ctx, prm, mat, plan, i);
    table.add(prm.pressures[i], prod);
    finished.add(prod);
    // A checkpoint after every point but the last: the point is where an
    // isotherm can stop and go on exactly. A stop request waits for it.
    if (!checkpoints.enabled() || i + 1 == n) continue;
    const auto step = static_cast<std::int64_t>(i + 1) * plan.per_point;
    const std::string file = checkpoints.write(step, static_cast<double>(step) * prm.timestep,
                                               [&] { return finished.archive(); });
    if (checkpoints.stop_now()) {
      throw StageFailure(StageCheckpoints::stopped_message(step, plan.total, file));
    }
  }
  checkpoints.report(ctx.results());
  report_isotherm(ctx, prm, mat, plan, table);
}

}  // namespace pbms::md
