// md_driver: molecular dynamics through the LAMMPS library.

#include <fmt/format.h>

#include "eam_material_spec.hpp"
#include "md_bodies.hpp"
#include "md_elastic.hpp"
#include "md_isotherm.hpp"
#include "md_surface_energy.hpp"
#include "md_tension.hpp"
#include "pbms/driver/stage_kind.hpp"

int main(int argc, char** argv) {
  pbms::StageRegistry registry;
  registry.add<pbms::md::IsothermStage>();
  registry.add<pbms::md::ElasticStage>();
  registry.add<pbms::md::TensionStage>();
  registry.add<pbms::md::BodiesStage>();
  registry.add<pbms::md::SurfaceEnergyStage>();
  for (auto& m : pbms::md::eam_material_kinds()) registry.add_material(std::move(m));
  pbms::DriverInfo info{"md_driver", "md", {{"lammps", PBMS_LAMMPS_VERSION}}};
  return pbms::run_driver(argc, argv, info, registry);
}
