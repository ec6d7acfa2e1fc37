#include "pbms/config/workflow.hpp"

namespace pbms::config {

Param materials_schema() {
  using units::Dimension;
  const std::vector<Param> eam_fields = {
      Param::file("potential", "Potential file in LAMMPS setfl format").require(),
      Param::string("element", "Element name as listed in the potential file").def("Cu"),
      Param::real("mass", Dimension::kMass, "Atomic mass").require().above(0),
      Param::choice("lattice", {"fcc", "bcc"}, "Crystal structure").def("fcc"),
      Param::real("lattice_constant", Dimension::kLength,
                  "Zero-temperature lattice constant; the starting lattice of every MD stage")
          .require()
          .above(0),
  };
  Param material = Param::map(
      "material", {Param::choice("kind", {"eam_alloy", "eam_fs"}, "Interaction model").require()},
      "One material");
  material.discriminated_by("kind")
      .variant("eam_alloy", eam_fields, "Embedded-atom method, LAMMPS pair_style eam/alloy")
      .variant("eam_fs", eam_fields, "Finnis-Sinclair EAM, LAMMPS pair_style eam/fs");
  return Param::map_of("materials", material, "Named materials that stages refer to");
}

}  // namespace pbms::config
