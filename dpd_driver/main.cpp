// dpd_driver: the dissipative particle dynamics engine.

#include "pbms/driver/stage_kind.hpp"
#include "stage/concurrent_stage.hpp"
#include "stage/dpd_properties_stages.hpp"
#include "stage/dpd_run.hpp"
#include "stage/dpd_stage_params.hpp"

int main(int argc, char** argv) {
  pbms::StageRegistry registry;
  registry.add<pbms::dpd::DpdRunStage>();
  registry.add<pbms::dpd::DpdEquilibrateStage>();
  registry.add<pbms::dpd::DpdElasticStage>();
  registry.add<pbms::dpd::DpdIsothermStage>();
  registry.add<pbms::dpd::DpdUniaxialStrainStage>();
  registry.add<pbms::dpd::DpdSurfaceEnergyStage>();
  registry.add<pbms::dpd::ConcurrentStage>();
  registry.add_material(pbms::dpd::MesoparticleMaterial::spec());
  pbms::DriverInfo info{"dpd_driver", "dpd", {}};
  return pbms::run_driver(argc, argv, info, registry);
}
