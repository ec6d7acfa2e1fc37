#include "md_elastic.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "md_setup.hpp"
#include "pbms/analysis/cubic_moduli.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/driver/stage_checkpoints.hpp"
#include "pbms/error.hpp"
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
  s.material_kinds = {"eam_alloy", "eam_fs", "sutton_chen"};
  s.cacheable = true;
  s.checkpoints = true;
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

// The stage's parameters (schema and defaults: spec() above); times in ps,
// temperatures in K, lengths in Å.
struct ElasticParams {
  std::string material;
  std::array<int, 3> cells{};
  double strain = 0.0;
  double strain_at_temperature = 0.0;
  double temperature = 0.0;                // 0: at 0 K only
  std::optional<double> lattice_constant;  // at `temperature`; empty: the material's
  double timestep = 0.0;
  double equilibration = 0.0;
  double production = 0.0;

  static ElasticParams from_yaml(const YAML::Node& p);
};

ElasticParams ElasticParams::from_yaml(const YAML::Node& p) {
  ElasticParams r;
  r.material = p["material"].as<std::string>();
  r.cells = cells_of(p["cells"]);
  r.strain = p["strain"].as<double>();
  r.strain_at_temperature = p["strain_at_temperature"].as<double>();
  r.temperature = p["temperature"].as<double>();
  if (p["lattice_constant"]) r.lattice_constant = p["lattice_constant"].as<double>();
  r.timestep = p["timestep"].as<double>();
  r.equilibration = p["equilibration"].as<double>();
  r.production = p["production"].as<double>();
  return r;
}

struct Stress {
  double xx, yy, zz, xy;  // GPa, tension positive
};

enum class Mode { kNormal, kShear };

// Strain the relaxed box, then read the stress: at 0 K after relaxing the
// atoms, at T as an NVT average.
Stress strained_stress(StageContext& ctx, const MdMaterial& mat, const ElasticParams& prm, double a,
                       Mode mode, double e, double temperature, const std::string& tag,
                       int64_t salt) {
  const auto& cells = prm.cells;
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
    const double dt = prm.timestep;
    lmp.command(fmt::format("timestep {}", dt));
    lmp.command(fmt::format("velocity all create {} {} mom yes rot yes dist gaussian",
                            2.0 * temperature, lammps_seed(ctx.seed(), 100 + salt)));
    lmp.command(fmt::format("fix nvt all nvt temp {0} {0} 0.1", temperature));
    lmp.run(steps_for(prm.equilibration, dt), 1000000, {});
    lmp.command("variable pxx equal pxx");
    lmp.command("variable pyy equal pyy");
    lmp.command("variable pzz equal pzz");
    lmp.command("variable pxy equal pxy");
    lmp.command("fix samples all vector 10 v_pxx v_pyy v_pzz v_pxy");
    lmp.run(steps_for(prm.production, dt), 1000000, {});
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

// The `strains` table: every applied strain and the stress it gave.
struct StrainTable {
  std::vector<double> t, mode, e, xx, yy, zz, xy;

  void add(double temperature, int m, double strain, const Stress& s) {
    t.push_back(temperature);
    mode.push_back(m);
    e.push_back(strain);
    xx.push_back(s.xx);
    yy.push_back(s.yy);
    zz.push_back(s.zz);
    xy.push_back(s.xy);
  }
  [[nodiscard]] int64_t rows() const { return static_cast<int64_t>(t.size()); }
  [[nodiscard]] Stress stress(std::size_t row) const {
    return {xx.at(row), yy.at(row), zz.at(row), xy.at(row)};
  }

  // The rows as a checkpoint holds them, and back.
  [[nodiscard]] CheckpointArchive archive() const {
    CheckpointArchive a;
    a.put("strains/temperature", t);
    a.put("strains/mode", mode);
    a.put("strains/strain", e);
    a.put("strains/stress_xx", xx);
    a.put("strains/stress_yy", yy);
    a.put("strains/stress_zz", zz);
    a.put("strains/stress_xy", xy);
    return a;
  }
  void load(const CheckpointArchive& a) {
    t = a.get("strains/temperature");
    mode = a.get("strains/mode");
    e = a.get("strains/strain");
    xx = a.get("strains/stress_xx");
    yy = a.get("strains/stress_yy");
    zz = a.get("strains/stress_zz");
    xy = a.get("strains/stress_xy");
  }

  void write(StageResults& r) const {
    r.add_column("strains", "temperature", "K", t);
    r.add_column("strains", "mode", "1", mode);  // 0: xx, 1: xy (engineering shear)
    r.add_column("strains", "strain", "1", e);
    r.add_column("strains", "stress_xx", "GPa", xx);
    r.add_column("strains", "stress_yy", "GPa", yy);
    r.add_column("strains", "stress_zz", "GPa", zz);
    r.add_column("strains", "stress_xy", "GPa", xy);
  }
};

// A checkpoint after each strained state but the last: each state is its
// own LAMMPS run from its own seed, so a resumed stage runs the others
// exactly as they would have run. A checkpoint's step counts the finished
// states; a stop request waits for the running one.
class FinishedStates {
 public:
  FinishedStates(StageContext& ctx, int total) : checkpoints_(ctx), total_(total) {}

  // The states the checkpoint a resumed run goes on from holds.
  void resume(StrainTable& table) {
    if (checkpoints_.enabled() && checkpoints_.resuming()) {
      table.load(checkpoints_.resume_archive());
    }
  }
  // After each finished state. Collective.
  void finished(const StrainTable& table) {
    const std::int64_t step = table.rows();
    if (!checkpoints_.enabled() || step == total_) return;
    const std::string file = checkpoints_.write(step, 0.0, [&] { return table.archive(); });
    if (checkpoints_.stop_now()) {
      throw StageFailure(StageCheckpoints::stopped_message(step, total_, file));
    }
  }
  void report(StageResults& r) const { checkpoints_.report(r); }

 private:
  StageCheckpoints checkpoints_;
  std::int64_t total_;
};

// The four strains (xx and xy, each + and -) at temperature t on a crystal
// of lattice constant a, and the moduli from their central differences.
// States the table already holds (a resumed stage's) are not run again.
analysis::CubicModuli measure(StageContext& ctx, const MdMaterial& mat, const ElasticParams& prm,
                              double t, double a, StrainTable& table, FinishedStates& finished) {
  const double e = t > 0 ? prm.strain_at_temperature : prm.strain;
  // Progress counts the strains of the whole stage, hot ones included.
  const int total = prm.temperature > 0 ? 8 : 4;
  const int first = t > 0 ? 4 : 0;  // the table's row of this temperature's first state
  Stress s[2][2];                   // [mode][sign]
  for (int m = 0; m < 2; ++m) {
    for (int sign = 0; sign < 2; ++sign) {
      const int row = first + m * 2 + sign;
      if (row < table.rows()) {
        s[m][sign] = table.stress(static_cast<std::size_t>(row));
        continue;
      }
      const double strain = sign == 0 ? e : -e;
      const std::string tag = fmt::format("{}_{}_{}", t > 0 ? "hot" : "cold", m == 0 ? "xx" : "xy",
                                          sign == 0 ? "plus" : "minus");
      s[m][sign] = strained_stress(ctx, mat, prm, a, m == 0 ? Mode::kNormal : Mode::kShear, strain,
                                   t, tag, m * 2 + sign);
      table.add(t, m, strain, s[m][sign]);
      ctx.progress(table.rows(), total, 0.0, tag);
      finished.finished(table);
    }
  }
  return analysis::CubicModuli{(s[0][0].xx - s[0][1].xx) / (2 * e),
                               (s[0][0].yy - s[0][1].yy) / (2 * e),
                               (s[1][0].xy - s[1][1].xy) / (2 * e)};
}

// The 0 K lattice parameter, from relaxing the box at zero pressure.
double relaxed_lattice_parameter(StageContext& ctx, const MdMaterial& mat,
                                 const std::array<int, 3>& cells) {
  Lammps lmp(ctx.comm(), ctx.stage_dir() / "relax.log");
  build_crystal(lmp, mat, mat.lattice_constant, cells, "p p p");
  lmp.command("fix relax all box/relax iso 0.0 vmax 0.001");
  lmp.command("minimize 0 1e-12 10000 100000");
  lmp.command("run 0");
  return lmp.thermo("lx") / cells[0];
}

}  // namespace

void ElasticStage::run(StageContext& ctx) {
  const ElasticParams prm = ElasticParams::from_yaml(ctx.params());
  const MdMaterial mat = material_of(ctx, prm.material);
  const double temperature = prm.temperature;
  const double a_t = prm.lattice_constant.value_or(mat.lattice_constant);
  auto& r = ctx.results();
  StrainTable table;
  FinishedStates finished(ctx, temperature > 0 ? 8 : 4);
  finished.resume(table);
  r.add_scalar("lattice_parameter", relaxed_lattice_parameter(ctx, mat, prm.cells), "Å");
  const analysis::CubicModuli cold =
      measure(ctx, mat, prm, 0.0, mat.lattice_constant, table, finished);
  r.add_scalar("c11", cold.c11, "GPa");
  r.add_scalar("c12", cold.c12, "GPa");
  r.add_scalar("c44", cold.c44, "GPa");
  r.add_scalar("bulk_modulus", cold.bulk_modulus(), "GPa");
  r.add_scalar("youngs_modulus_100", cold.youngs_modulus_100(), "GPa");
  if (temperature > 0) {
    const analysis::CubicModuli hot = measure(ctx, mat, prm, temperature, a_t, table, finished);
    r.add_scalar("c11_at_t", hot.c11, "GPa");
    r.add_scalar("c12_at_t", hot.c12, "GPa");
    r.add_scalar("c44_at_t", hot.c44, "GPa");
  }
  table.write(r);
  finished.report(r);
}

}  // namespace pbms::md
