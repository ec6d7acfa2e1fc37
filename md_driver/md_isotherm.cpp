#include "md_isotherm.hpp"

#include <cmath>

#include <fmt/format.h>

#include "md_setup.hpp"
#include "pbms/analysis/block_average.hpp"
#include "pbms/analysis/equation_of_state.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::md {

using config::OutputSpec;
using config::Param;
using units::Dimension;

config::StageKindSpec IsothermStage::spec() {
  config::StageKindSpec s;
  s.kind = "md_isotherm";
  s.program = "md_driver";
  s.doc =
      "Pressure-volume isotherm of a periodic crystal by NPT MD (Nose-Hoover), with a "
      "Birch-Murnaghan fit";
  s.material_kinds = {"eam_alloy", "eam_fs"};
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
       "Mean lattice parameter at the lowest pressure"},
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

void IsothermStage::run(StageContext& ctx) {
  const YAML::Node& p = ctx.params();
  const MdMaterial mat = material_of(ctx);
  const double temperature = p["temperature"].as<double>();
  const auto pressures = p["pressures"].as<std::vector<double>>();
  const auto cells = cells_of(p["cells"]);
  const double dt = p["timestep"].as<double>();
  const int64_t n_equil = steps_for(p["equilibration"].as<double>(), dt);
  const int64_t n_prod = steps_for(p["production"].as<double>(), dt);
  const int64_t every = p["sample_every"].as<int64_t>();
  const double tdamp = p["thermostat_damping"].as<double>();
  const double pdamp = p["barostat_damping"].as<double>();
  const int64_t traj_every = p["trajectory_every"].as<int64_t>();
  if (n_prod < 10 * every) {
    throw Error(
        fmt::format("stage '{}': production ({} steps) must span at least 10 samples "
                    "(sample_every = {})",
                    ctx.stage(), n_prod, every));
  }
  const int64_t per_point = n_equil + n_prod;
  const int64_t total = per_point * static_cast<int64_t>(pressures.size());
  const double natoms_per_cell = mat.lattice == "fcc" ? 4.0 : 2.0;
  const double n_atoms = natoms_per_cell * cells[0] * cells[1] * cells[2];

  std::vector<double> p_target, p_mean, p_err, vol, vol_err, alat, alat_err, temp;
  for (size_t i = 0; i < pressures.size(); ++i) {
    const std::string tag = fmt::format("p{}", i);
    const std::string phase_label = fmt::format("P = {:.4g} GPa", pressures[i] / 1e4);
    Lammps lmp(ctx.comm(), ctx.stage_dir() / (tag + ".log"));
    lmp.comment(fmt::format("PBMS md_isotherm '{}', point {} of {}: {} K, {} bar", ctx.stage(),
                            i + 1, pressures.size(), temperature, pressures[i]));
    build_crystal(lmp, mat, mat.lattice_constant, cells, "p p p");
    lmp.command(fmt::format("timestep {}", dt));
    lmp.command(fmt::format("velocity all create {} {} mom yes rot yes dist gaussian",
                            2.0 * temperature, lammps_seed(ctx.seed(), i)));
    lmp.command(fmt::format("fix npt all npt temp {0} {0} {1} iso {2} {2} {3}", temperature, tdamp,
                            pressures[i], pdamp));
    lmp.command("thermo 1000");
    lmp.command("thermo_style custom step temp press vol lx pe");
    TrajectoryRecorder traj(ctx, lmp, tag + ".h5md", traj_every, {true, true, true});
    const int64_t base = static_cast<int64_t>(i) * per_point;
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
    lmp.command(fmt::format("variable vatom equal vol/{}", n_atoms));
    lmp.command(fmt::format("fix samples all vector {} c_thermo_press v_vatom v_alat c_thermo_temp",
                            every));
    lmp.command(fmt::format("fix means all ave/time {0} {1} {2} c_thermo_press v_vatom v_alat",
                            every, n_prod / every, n_prod / every * every));
    lmp.run(n_prod, chunk_for(total, traj_every), report("production", n_equil));
    // Replayed by a plain `lmp -in` this prints the same averages.
    lmp.command(
        "print \"PBMS_AVERAGES pressure $(f_means[1]) volume_per_atom $(f_means[2]) "
        "lattice_parameter $(f_means[3])\"");

    const auto rows = lmp.fix_array("samples", 4);
    // Drop the sample taken at the first production step (end of the
    // equilibration): only the production window is averaged.
    std::vector<std::vector<double>> prod(rows.begin() + (rows.size() > 1 ? 1 : 0), rows.end());
    const auto press = column(prod, 0), va = column(prod, 1), aa = column(prod, 2),
               tt = column(prod, 3);
    p_target.push_back(pressures[i]);
    p_mean.push_back(analysis::mean(press));
    p_err.push_back(analysis::block_average(press, 10).error);
    vol.push_back(analysis::mean(va));
    vol_err.push_back(analysis::block_average(va, 10).error);
    alat.push_back(analysis::mean(aa));
    alat_err.push_back(analysis::block_average(aa, 10).error);
    temp.push_back(analysis::mean(tt));
    if (ctx.rank() == 0) {
      lmp.write_script(
          ctx.stage_dir() / (tag + ".in"),
          fmt::format("md_isotherm point {}: T = {} K, P = {} bar", i, temperature, pressures[i]));
      ctx.results().files.push_back(ctx.stage() + "/" + tag + ".in");
      if (traj.enabled()) ctx.results().files.push_back(traj.relative_path());
    }
  }

  // Fit against the measured mean pressures: they, not the targets, belong
  // to the measured volumes.
  const auto fit = analysis::fit_birch_murnaghan(vol, p_mean);
  std::vector<double> ratio, ratio_err;
  for (size_t i = 0; i < vol.size(); ++i) {
    ratio.push_back(vol[i] / fit.v0);
    ratio_err.push_back(vol_err[i] / fit.v0);
  }
  size_t lowest = 0;
  for (size_t i = 1; i < pressures.size(); ++i) {
    if (pressures[i] < pressures[lowest]) lowest = i;
  }
  auto& r = ctx.results();
  r.add_scalar("lattice_parameter", alat[lowest], "Å", alat_err[lowest]);
  r.add_scalar("bulk_modulus", fit.b0 / units::kBarPerGPa, "GPa");
  r.add_scalar("bulk_modulus_derivative", fit.b0_prime, "1");
  r.add_scalar("equilibrium_volume", fit.v0, "Å^3");
  r.add_scalar("fit_rms_residual", fit.rms_residual / units::kBarPerGPa, "GPa");
  r.add_column("isotherm", "pressure_target", "bar", p_target);
  r.add_column("isotherm", "pressure", "bar", p_mean);
  r.add_column("isotherm", "pressure_std_error", "bar", p_err);
  r.add_column("isotherm", "volume_per_atom", "Å^3", vol);
  r.add_column("isotherm", "volume_per_atom_std_error", "Å^3", vol_err);
  r.add_column("isotherm", "volume_ratio", "1", ratio);
  r.add_column("isotherm", "volume_ratio_std_error", "1", ratio_err);
  r.add_column("isotherm", "lattice_parameter", "Å", alat);
  r.add_column("isotherm", "lattice_parameter_std_error", "Å", alat_err);
  r.add_column("isotherm", "temperature", "K", temp);
  r.attributes["material"] = mat.name;
  r.attributes["potential"] = mat.potential;
  r.attributes["atoms"] = fmt::format("{}", static_cast<int64_t>(n_atoms));
}

}  // namespace pbms::md
