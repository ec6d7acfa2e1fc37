// dpd_elastic, dpd_isotherm, dpd_uniaxial_strain and dpd_surface_energy: properties of the periodic
// bulk DPD crystal of a dpd_mesoparticle material, computed in process by the calculators of
// properties/ (the same calls the MD->DPD fit makes). The crystal is small
// (hundreds of particles), so rank 0 computes and the other ranks wait.
#pragma once

#include "pbms/driver/stage_kind.hpp"

namespace pbms::dpd {

class DpdElasticStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

class DpdIsothermStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

class DpdUniaxialStrainStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

class DpdSurfaceEnergyStage : public StageKind {
 public:
  static config::StageKindSpec spec();
  void run(StageContext& ctx) override;
};

}  // namespace pbms::dpd
