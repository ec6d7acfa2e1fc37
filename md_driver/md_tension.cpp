#include "md_tension.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "md_setup.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::md {

using config::OutputSpec;
using config::Param;
using units::Dimension;

config::StageKindSpec TensionStage::spec() {
  config::StageKindSpec s;
  s.kind = "md_tension";
  s.program = "md_driver";
  s.doc =
      "Tension of a nanowire with free surfaces, pulled along x by rigid grips at a "
      "constant strain rate, Nose-Hoover NVT";
  s.material_kinds = {"eam_alloy", "eam_fs"};
  s.cacheable = true;
  s.params = {
      Param::identifier("material", "Material to simulate").require().material(),
      Param::int_list("cells", "Wire size in unit cells (length x, cross-section y, z)")
          .def(std::vector<int>{40, 10, 10})
          .length(3, 3)
          .at_least(2),
      Param::real("lattice_constant", Dimension::kLength,
                  "Lattice constant at the test temperature; defaults to the material's")
          .above(0)
          .referable(),
      Param::real("temperature", Dimension::kTemperature, "Temperature").def(300.0).above(0),
      Param::real("strain_rate", Dimension::kRate, "Engineering strain rate of the gauge")
          .def(1.0e-3)
          .above(0),
      Param::real("max_strain", Dimension::kNone, "Strain at which the test stops")
          .def(0.1)
          .above(0)
          .at_most(2.0),
      Param::real("fit_max_strain", Dimension::kNone,
                  "Young's modulus is fitted to strains up to this value")
          .def(0.02)
          .above(0),
      Param::integer("grip_cells", "Thickness of each rigid grip in unit cells").def(2).at_least(1),
      Param::real("timestep", Dimension::kTime, "MD time step").def(0.002).above(0).at_most(0.01),
      Param::real("equilibration", Dimension::kTime, "NVT time before loading")
          .def(10.0)
          .at_least(0),
      Param::integer("sample_every", "Steps between stress samples").def(50).above(0),
      Param::integer("trajectory_every", "Steps between H5MD frames; 0 writes none")
          .def(0)
          .at_least(0),
  };
  s.outputs = {
      {"youngs_modulus", OutputSpec::Shape::kScalar, "GPa",
       "Slope of the gauge's virial stress vs strain up to fit_max_strain"},
      {"youngs_modulus_grip_force", OutputSpec::Shape::kScalar, "GPa",
       "The same slope from the grip forces over the initial cross-section"},
      {"ultimate_stress", OutputSpec::Shape::kScalar, "GPa", "Largest stress reached"},
      {"strain_at_ultimate", OutputSpec::Shape::kScalar, "1", "Strain at the largest stress"},
      {"stress_strain", OutputSpec::Shape::kTable, "",
       "Strain, virial stress, grip-force stress and temperature"},
  };
  return s;
}

void TensionStage::run(StageContext& ctx) {
  const YAML::Node& p = ctx.params();
  const MdMaterial mat = material_of(ctx);
  const auto cells = cells_of(p["cells"]);
  const double a =
      p["lattice_constant"] ? p["lattice_constant"].as<double>() : mat.lattice_constant;
  const double temperature = p["temperature"].as<double>();
  const double rate = p["strain_rate"].as<double>();
  const double max_strain = p["max_strain"].as<double>();
  const double fit_max = p["fit_max_strain"].as<double>();
  const int grip = p["grip_cells"].as<int>();
  const double dt = p["timestep"].as<double>();
  const int64_t n_equil = steps_for(p["equilibration"].as<double>(), dt);
  const int64_t every = p["sample_every"].as<int64_t>();
  const int64_t traj_every = p["trajectory_every"].as<int64_t>();
  if (2 * grip >= cells[0] - 1) {
    throw Error(fmt::format("stage '{}': grips of {} cells leave no wire between them in {} cells",
                            ctx.stage(), grip, cells[0]));
  }
  const double area = cells[1] * a * cells[2] * a;
  const int64_t n_load = steps_for(max_strain / rate, dt);
  const int64_t total = n_equil + n_load;

  Lammps lmp(ctx.comm(), ctx.stage_dir() / "tension.log");
  lmp.comment(fmt::format("PBMS md_tension '{}': {}x{}x{} cells, {} K, strain rate {} 1/ps",
                          ctx.stage(), cells[0], cells[1], cells[2], temperature, rate));
  build_crystal(lmp, mat, a, cells, "s s s");
  lmp.command(fmt::format("timestep {}", dt));
  // Relax the surfaces at 0 K first: a thin wire cut from bulk contracts by
  // ~1 %, and doing that in MD would leave it ringing axially for many ps.
  lmp.command("minimize 0 1e-8 1000 10000");
  // The wire then equilibrates free: surface stress shortens a thin wire,
  // and holding its ends at the bulk spacing would pre-stress it by GPa.
  lmp.command(fmt::format("velocity all create {} {} mom yes rot yes dist gaussian",
                          2.0 * temperature, lammps_seed(ctx.seed(), 7)));
  lmp.command(fmt::format("fix nvt all nvt temp {0} {0} 0.1", temperature));
  lmp.command("fix no_drift all momentum 100 linear 1 1 1 angular");
  lmp.command("thermo_style custom step temp pe lx");
  lmp.command("thermo 1000");
  TrajectoryRecorder traj(ctx, lmp, "tension.h5md", traj_every, {false, false, false});
  traj.maybe_write(0, 0.0);
  const int64_t chunk = chunk_for(total, traj_every);
  if (n_equil > 0) {
    lmp.run(n_equil, chunk, [&](int64_t done) {
      traj.maybe_write(done, done * dt);
      ctx.progress(done, total, done * dt, "equilibration");
    });
  }
  lmp.command("unfix nvt");
  lmp.command("unfix no_drift");

  // Grips: end slabs of the relaxed wire, moved rigidly at +/- v.
  lmp.command("variable xlo equal bound(all,xmin)");
  lmp.command("variable xhi equal bound(all,xmax)");
  const double xlo = lmp.variable("xlo"), xhi = lmp.variable("xhi");
  const double grip_len = grip * a;
  const double gauge = xhi - xlo - 2.0 * grip_len;
  const double grip_speed = 0.5 * rate * gauge;
  lmp.command(
      fmt::format("region left_grip block INF {:.10g} INF INF INF INF units box", xlo + grip_len));
  lmp.command(
      fmt::format("region right_grip block {:.10g} INF INF INF INF INF units box", xhi - grip_len));
  lmp.command("group left region left_grip");
  lmp.command("group right region right_grip");
  lmp.command("group grips union left right");
  lmp.command("group wire subtract all grips");
  lmp.command("fix hold_left left setforce 0 0 0");
  lmp.command("fix hold_right right setforce 0 0 0");
  lmp.command("fix move_grips grips nve");
  lmp.command(fmt::format("fix nvt wire nvt temp {0} {0} 0.1", temperature));
  lmp.command("compute wire_temp wire temp");
  lmp.command("reset_timestep 0");
  lmp.command(fmt::format("velocity left set {} 0 0 units box", -grip_speed));
  lmp.command(fmt::format("velocity right set {} 0 0 units box", grip_speed));
  // The wire starts from the matching linear velocity profile, so no shock
  // is launched from the grips.
  lmp.command(fmt::format("velocity wire ramp vx {} {} x {:.10g} {:.10g} sum yes units box",
                          -grip_speed, grip_speed, xlo + grip_len, xhi - grip_len));
  // Two measures of the axial stress, each averaged over a sampling window:
  // the virial stress of the gauge atoms (as the seed computes it), and the
  // force the wire exerts on the grips (read before setforce zeroes it) over
  // the initial cross-section. The first is far less noisy; both must agree.
  const double to_gpa = 1.0 / units::kBarPerGPa;
  lmp.command("compute atom_stress wire stress/atom NULL");
  lmp.command("compute wire_sxx wire reduce sum c_atom_stress[1]");
  lmp.command(
      fmt::format("variable gauge_length equal {:.12g}+{:.12g}*step*dt", gauge, 2.0 * grip_speed));
  lmp.command(fmt::format("variable virial_stress equal c_wire_sxx/({:.12g}*v_gauge_length)*{}",
                          area, to_gpa));
  lmp.command(
      fmt::format("variable grip_stress equal (f_hold_left[1]-f_hold_right[1])/(2*{:.12g})*{:.12g}",
                  area, units::kBarPerEvPerA3 * to_gpa));
  lmp.command(
      fmt::format("fix stress_avg all ave/time 1 {0} {0} v_virial_stress v_grip_stress", every));
  // Strain at the middle of the window the stress was averaged over.
  lmp.command(
      fmt::format("variable strain equal (step-{:.1f})*dt*{:.12g}", 0.5 * (every - 1), rate));
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
  lmp.run(n_load, chunk, [&](int64_t done) {
    traj.maybe_write(n_equil + done, (n_equil + done) * dt);
    ctx.progress(n_equil + done, total, (n_equil + done) * dt,
                 fmt::format("strain {:.4f}", done * dt * rate));
  });
  auto rows = lmp.fix_array("samples", 4);
  // Row 0 is step 0, before any window was averaged.
  if (!rows.empty()) rows.erase(rows.begin());
  const auto strain = column(rows, 0), stress = column(rows, 1), grip_stress = column(rows, 2),
             temp = column(rows, 3);

  auto elastic_fit = [&](const std::vector<double>& y) {
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
    return analysis::fit_line(fx, fy);
  };
  const auto fit = elastic_fit(stress);
  const auto grip_fit = elastic_fit(grip_stress);
  const auto peak = std::max_element(stress.begin(), stress.end()) - stress.begin();
  auto& r = ctx.results();
  r.add_scalar("youngs_modulus", fit.slope, "GPa", fit.slope_error);
  r.add_scalar("youngs_modulus_grip_force", grip_fit.slope, "GPa", grip_fit.slope_error);
  r.add_scalar("ultimate_stress", stress[static_cast<size_t>(peak)], "GPa");
  r.add_scalar("strain_at_ultimate", strain[static_cast<size_t>(peak)], "1");
  r.add_column("stress_strain", "strain", "1", strain);
  r.add_column("stress_strain", "stress", "GPa", stress);
  r.add_column("stress_strain", "grip_stress", "GPa", grip_stress);
  r.add_column("stress_strain", "temperature", "K", temp);
  r.attributes["fit_max_strain"] = fmt::format("{}", fit_max);
  r.attributes["fit_intercept_gpa"] = fmt::format("{}", fit.intercept);
  if (ctx.rank() == 0) {
    lmp.write_script(ctx.stage_dir() / "tension.in", "md_tension " + ctx.stage());
    r.files.push_back(ctx.stage() + "/tension.in");
    if (traj.enabled()) r.files.push_back(traj.relative_path());
  }
}

}  // namespace pbms::md
