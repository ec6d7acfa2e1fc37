#include "md_surface_energy.hpp"

#include <array>
#include <string>

#include <fmt/format.h>

#include "md_setup.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::md {

using config::OutputSpec;
using config::Param;

config::StageKindSpec SurfaceEnergyStage::spec() {
  config::StageKindSpec s;
  s.kind = "md_surface_energy";
  s.program = "md_driver";
  s.doc =
      "(100) surface energy at 0 K: a crystal relaxed at zero pressure, opened along z into a "
      "slab with two free (100) faces, against its bulk energy; unrelaxed and with the atoms "
      "relaxed";
  s.material_kinds = {"eam_alloy", "eam_fs", "sutton_chen"};
  s.cacheable = true;
  s.params = {
      Param::identifier("material", "Material to simulate").require().material(),
      Param::int_list("cells",
                      "Unit cells along x, y (periodic) and z (the slab's thickness: two "
                      "(100) planes a cell)")
          .def(std::vector<int>{4, 4, 12})
          .length(3, 3)
          .at_least(2),
  };
  s.outputs = {
      {"surface_energy_100", OutputSpec::Shape::kScalar, "J/m^2",
       "Energy per area of each (100) face, atoms relaxed"},
      {"surface_energy_100_unrelaxed", OutputSpec::Shape::kScalar, "J/m^2",
       "The same with the atoms on their bulk sites"},
      {"cohesive_energy", OutputSpec::Shape::kScalar, "eV",
       "Energy per atom of the bulk crystal (negative when bound)"},
      {"lattice_parameter", OutputSpec::Shape::kScalar, "Å", "Relaxed lattice parameter, 0 K"},
  };
  return s;
}

namespace {

// The stage's parameters (schema and defaults: spec() above).
struct SurfaceEnergyParams {
  std::string material;
  std::array<int, 3> cells{};

  static SurfaceEnergyParams from_yaml(const YAML::Node& p) {
    return {p["material"].as<std::string>(), cells_of(p["cells"])};
  }
};

}  // namespace

void SurfaceEnergyStage::run(StageContext& ctx) {
  const SurfaceEnergyParams prm = SurfaceEnergyParams::from_yaml(ctx.params());
  const MdMaterial mat = material_of(ctx, prm.material);
  const std::array<int, 3>& cells = prm.cells;
  Lammps lmp(ctx.comm(), ctx.stage_dir() / "lammps.log");
  build_crystal(lmp, mat, mat.lattice_constant, cells, "p p p");
  lmp.command("thermo_style custom step pe atoms lx ly lz zlo zhi");
  // The bulk at zero pressure: its box relaxed, as md_elastic's reference.
  // A force tolerance of 1e-10 eV/Å: at 1e-12 nickel's box relaxation on
  // one rank ran its 10,000 iterations (31 s) without meeting it, for a
  // lattice constant that 1e-10 gives to 1e-9 Å.
  lmp.command("fix relax all box/relax iso 0.0 vmax 0.001");
  lmp.command("minimize 0 1e-10 10000 100000");
  lmp.command("unfix relax");
  lmp.command("run 0");
  const auto atoms = static_cast<double>(lmp.natoms());
  const double bulk = lmp.thermo("pe") / atoms;
  const double area = lmp.thermo("lx") * lmp.thermo("ly");
  const double lattice = lmp.thermo("lx") / cells[0];
  // Opened: z no longer periodic, with room on both sides of the slab for
  // the faces to relax into. Every atom keeps its site. (The box relaxation
  // moved both ends of the box, so the room is taken from where they are.)
  const double lz = lmp.thermo("lz"), zlo = lmp.thermo("zlo"), zhi = lmp.thermo("zhi");
  lmp.command(fmt::format("change_box all z final {:.10g} {:.10g} boundary p p f", zlo - 0.5 * lz,
                          zhi + 0.5 * lz));
  lmp.command("run 0");
  const auto gamma = [&] {
    return (lmp.thermo("pe") - atoms * bulk) / (2.0 * area) * units::kJoulePerM2PerEvPerA2;
  };
  const double unrelaxed = gamma();
  lmp.command("minimize 0 1e-12 10000 100000");
  lmp.command("run 0");
  const double relaxed = gamma();
  if (!(relaxed > 0.0) || relaxed > unrelaxed * (1.0 + 1e-9)) {
    throw StageFailure(fmt::format(
        "the relaxed (100) surface energy {:.6g} J/m^2 is not positive or above the unrelaxed "
        "{:.6g}: the slab fell apart or reconstructed",
        relaxed, unrelaxed));
  }
  lmp.command(
      fmt::format("print \"PBMS_SURFACE unrelaxed {:.12g} relaxed {:.12g}\"", unrelaxed, relaxed));
  if (ctx.rank() == 0) lmp.write_script(ctx.stage_dir() / "surface.in", "md_surface_energy");
  auto& r = ctx.results();
  r.add_scalar("surface_energy_100", relaxed, "J/m^2");
  r.add_scalar("surface_energy_100_unrelaxed", unrelaxed, "J/m^2");
  r.add_scalar("cohesive_energy", bulk, "eV");
  r.add_scalar("lattice_parameter", lattice, "Å");
}

}  // namespace pbms::md
