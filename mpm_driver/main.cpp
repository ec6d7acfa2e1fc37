// mpm_driver: the material point method engine.

#include "materials/material_registry.hpp"
#include "pbms/driver/stage_kind.hpp"
#include "stage/concurrent_mpm_part.hpp"
#include "stage/mpm_run.hpp"

int main(int argc, char** argv) {
  pbms::StageRegistry registry;
  registry.add<pbms::mpm::MpmRunStage>();
  registry.add<pbms::mpm::ConcurrentMpmPart>();
  for (auto& m : pbms::mpm::MaterialRegistry::specs()) registry.add_material(std::move(m));
  pbms::DriverInfo info{"mpm_driver", "mpm", {}};
  return pbms::run_driver(argc, argv, info, registry);
}
