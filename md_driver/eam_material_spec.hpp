// The material kinds md_driver's stages take: embedded-atom potentials of a
// LAMMPS setfl file (eam_alloy, eam_fs), and Sutton-Chen, which md_driver
// tabulates as one (sutton_chen_setfl.hpp). Their keys are read into
// MdMaterial (md_setup.hpp).
#pragma once

#include <vector>

#include "pbms/config/stage_kind_spec.hpp"

namespace pbms::md {

[[nodiscard]] std::vector<config::MaterialKindSpec> eam_material_kinds();

}  // namespace pbms::md
