#include "md_elastic.hpp"

#include <fmt/format.h>

#include "md_setup.hpp"
#include "pbms/analysis/cubic_moduli.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/units.hpp"

namespace pbms::md {

using config::OutputSpec;
using config::Param;
using units::Dimension;

config::StageKindSpec ElasticStage::spec() {
  config::StageKindSpec s;
  s.kind = "md_elastic";
  s.program = "md_driver";
  s.doc =
      "Cubic elastic constants from +/- finite strains: relaxed at 0 K, and optionally "
      "averaged by NVT MD at a temperature";
  s.material_kinds = {"eam_alloy", "eam_fs"};
  s.cacheable = true;
  s.params = {
      Param::identifier("material", "Material to simulate").require().material(),
      Param::int_list("cells", "Unit cells along x, y, z")
          .def(std::vector<int>{4, 4, 4})
          .length(3, 3)
          .at_least(2),
      Param::real("strain", Dimension::kNone, "Magnitude of the applied strains at 0 K")
          .def(1.0e-3)
          .above(0)
          .at_most(0.05),
      Param::real("strain_at_temperature", Dimension::kNone,
                  "Magnitude of the strains at `temperature`: larger than at 0 K, since the "
                  "statistical error of the stress average is divided by it")
          .def(5.0e-3)
          .above(0)
          .at_most(0.05),
      Param::real("temperature", Dimension::kTemperature,
                  "If > 0, also measure the constants at this temperature by MD")
          .def(0.0)
          .at_least(0),
      Param::real("lattice_constant", Dimension::kLength,
                  "Lattice constant at `temperature` for the finite-T measurement; defaults "
                  "to the material's")
          .above(0)
          .referable(),
      Param::real("timestep", Dimension::kTime, "MD time step (finite T)").def(0.002).above(0),
      Param::real("equilibration", Dimension::kTime, "NVT time per strain before averaging")
          .def(5.0)
          .at_least(0),
      Param::real("production", Dimension::kTime, "NVT time averaged per strain")
          .def(20.0)
          .above(0),
  };
  s.outputs = {
      {"c11", OutputSpec::Shape::kScalar, "GPa", "C11 at 0 K"},
      {"c12", OutputSpec::Shape::kScalar, "GPa", "C12 at 0 K"},
      {"c44", OutputSpec::Shape::kScalar, "GPa", "C44 at 0 K"},
      {"bulk_modulus", OutputSpec::Shape::kScalar, "GPa", "(C11 + 2 C12) / 3 at 0 K"},
      {"youngs_modulus_100", OutputSpec::Shape::kScalar, "GPa", "Young's modulus along <100>"},
      {"lattice_parameter", OutputSpec::Shape::kScalar, "Å", "Relaxed lattice parameter, 0 K"},
      {"c11_at_t", OutputSpec::Shape::kScalar, "GPa", "C11 at `temperature` (if > 0)"},
      {"c12_at_t", OutputSpec::Shape::kScalar, "GPa", "C12 at `temperature` (if > 0)"},
      {"c44_at_t", OutputSpec::Shape::kScalar, "GPa", "C44 at `temperature` (if > 0)"},
      {"strains", OutputSpec::Shape::kTable, "", "Applied strains and the measured stresses"},
  };
  return s;
}

namespace {

struct Stress {
  double xx, yy, zz, xy;  // GPa, tension positive
};

enum class Mode { kNormal, kShear };

// Strain the relaxed box, then read the stress: at 0 K after relaxing the
// atoms, at T as an NVT average.
Stress strained_stress(StageContext& ctx, const MdMaterial& mat, const std::array<int, 3>& cells,
                       double a, Mode mode, double e, double temperature, const YAML::Node& p,
                       const std::string& tag, int64_t salt) {
  Lammps lmp(ctx.comm(), ctx.stage_dir() / (tag + ".log"));
  build_crystal(lmp, mat, a, cells, "p p p");
  lmp.command("change_box all triclinic");
  if (temperature <= 0.0) {
    // Relax the box first so the reference state is stress free.
    lmp.command("fix relax all box/relax aniso 0.0 vmax 0.001");
    lmp.command("minimize 0 1e-12 10000 100000");
    lmp.command("unfix relax");
  }
  if (mode == Mode::kNormal) {
    lmp.command(fmt::format("change_box all x scale {:.15g} remap", 1.0 + e));
  } else {
    lmp.command(fmt::format("change_box all xy final $(({:.15g})*ly) remap units box", e));
  }
  Stress s{};
  const double to_gpa = -1.0 / units::kBarPerGPa;  // LAMMPS pressure = -stress, in bar
  // pxx..pxy must be on the thermo line so that `run 0` evaluates them.
  lmp.command("thermo_style custom step pe press pxx pyy pzz pxy lx ly lz");
  if (temperature <= 0.0) {
    lmp.command("minimize 0 1e-12 10000 100000");
    lmp.command("run 0");
    lmp.command("print \"PBMS_STRESS_BAR pxx $(pxx) pyy $(pyy) pzz $(pzz) pxy $(pxy)\"");
    s = {lmp.thermo("pxx") * to_gpa, lmp.thermo("pyy") * to_gpa, lmp.thermo("pzz") * to_gpa,
         lmp.thermo("pxy") * to_gpa};
  } else {
    const double dt = p["timestep"].as<double>();
    lmp.command(fmt::format("timestep {}", dt));
    lmp.command(fmt::format("velocity all create {} {} mom yes rot yes dist gaussian",
                            2.0 * temperature, lammps_seed(ctx.seed(), 100 + salt)));
    lmp.command(fmt::format("fix nvt all nvt temp {0} {0} 0.1", temperature));
    lmp.run(steps_for(p["equilibration"].as<double>(), dt), 1000000, {});
    lmp.command("variable pxx equal pxx");
    lmp.command("variable pyy equal pyy");
    lmp.command("variable pzz equal pzz");
    lmp.command("variable pxy equal pxy");
    lmp.command("fix samples all vector 10 v_pxx v_pyy v_pzz v_pxy");
    lmp.run(steps_for(p["production"].as<double>(), dt), 1000000, {});
    // The means md_driver takes below, printed in full so that a plain
    // `lmp -in` of the script can be compared with them.
    lmp.command(
        "print \"PBMS_STRESS_BAR pxx $(ave(f_samples[1])) pyy $(ave(f_samples[2])) "
        "pzz $(ave(f_samples[3])) pxy $(ave(f_samples[4]))\"");
    const auto rows = lmp.fix_array("samples", 4);
    s = {analysis::mean(column(rows, 0)) * to_gpa, analysis::mean(column(rows, 1)) * to_gpa,
         analysis::mean(column(rows, 2)) * to_gpa, analysis::mean(column(rows, 3)) * to_gpa};
  }
  if (ctx.rank() == 0) lmp.write_script(ctx.stage_dir() / (tag + ".in"), "md_elastic " + tag);
  return s;
}

}  // namespace

void ElasticStage::run(StageContext& ctx) {
  const YAML::Node& p = ctx.params();
  const MdMaterial mat = material_of(ctx);
  const auto cells = cells_of(p["cells"]);
  const double e_cold = p["strain"].as<double>();
  const double e_hot = p["strain_at_temperature"].as<double>();
  const double temperature = p["temperature"].as<double>();
  const double a_t =
      p["lattice_constant"] ? p["lattice_constant"].as<double>() : mat.lattice_constant;
  auto& r = ctx.results();
  std::vector<double> col_t, col_mode, col_e, col_xx, col_yy, col_zz, col_xy;

  const int total = temperature > 0 ? 8 : 4;
  int done = 0;
  auto measure = [&](double t, double a) {
    const double e = t > 0 ? e_hot : e_cold;
    Stress s[2][2];  // [mode][sign]
    for (int m = 0; m < 2; ++m) {
      for (int sign = 0; sign < 2; ++sign) {
        const double strain = sign == 0 ? e : -e;
        const std::string tag = fmt::format("{}_{}_{}", t > 0 ? "hot" : "cold",
                                            m == 0 ? "xx" : "xy", sign == 0 ? "plus" : "minus");
        s[m][sign] = strained_stress(ctx, mat, cells, a, m == 0 ? Mode::kNormal : Mode::kShear,
                                     strain, t, p, tag, m * 2 + sign);
        col_t.push_back(t);
        col_mode.push_back(m);
        col_e.push_back(strain);
        col_xx.push_back(s[m][sign].xx);
        col_yy.push_back(s[m][sign].yy);
        col_zz.push_back(s[m][sign].zz);
        col_xy.push_back(s[m][sign].xy);
        ctx.progress(++done, total, 0.0, tag);
      }
    }
    return analysis::CubicModuli{(s[0][0].xx - s[0][1].xx) / (2 * e),
                                 (s[0][0].yy - s[0][1].yy) / (2 * e),
                                 (s[1][0].xy - s[1][1].xy) / (2 * e)};
  };

  // The 0 K lattice parameter comes from the first relaxation; record it.
  {
    Lammps lmp(ctx.comm(), ctx.stage_dir() / "relax.log");
    build_crystal(lmp, mat, mat.lattice_constant, cells, "p p p");
    lmp.command("fix relax all box/relax iso 0.0 vmax 0.001");
    lmp.command("minimize 0 1e-12 10000 100000");
    lmp.command("run 0");
    r.add_scalar("lattice_parameter", lmp.thermo("lx") / cells[0], "Å");
  }
  const analysis::CubicModuli cold = measure(0.0, mat.lattice_constant);
  r.add_scalar("c11", cold.c11, "GPa");
  r.add_scalar("c12", cold.c12, "GPa");
  r.add_scalar("c44", cold.c44, "GPa");
  r.add_scalar("bulk_modulus", cold.bulk_modulus(), "GPa");
  r.add_scalar("youngs_modulus_100", cold.youngs_modulus_100(), "GPa");
  if (temperature > 0) {
    const analysis::CubicModuli hot = measure(temperature, a_t);
    r.add_scalar("c11_at_t", hot.c11, "GPa");
    r.add_scalar("c12_at_t", hot.c12, "GPa");
    r.add_scalar("c44_at_t", hot.c44, "GPa");
  }
  r.add_column("strains", "temperature", "K", col_t);
  r.add_column("strains", "mode", "1", col_mode);  // 0: xx, 1: xy (engineering shear)
  r.add_column("strains", "strain", "1", col_e);
  r.add_column("strains", "stress_xx", "GPa", col_xx);
  r.add_column("strains", "stress_yy", "GPa", col_yy);
  r.add_column("strains", "stress_zz", "GPa", col_zz);
  r.add_column("strains", "stress_xy", "GPa", col_xy);
}

}  // namespace pbms::md
