#include "eam_material_spec.hpp"

namespace pbms::md {

std::vector<config::MaterialKindSpec> eam_material_kinds() {
  using config::Param;
  using units::Dimension;
  const std::vector<Param> fields = {
      Param::file("potential", "Potential file in LAMMPS setfl format").require(),
      Param::string("element", "Element name as listed in the potential file").def("Cu"),
      Param::real("mass", Dimension::kMass, "Atomic mass").require().above(0),
      Param::choice("lattice", {"fcc", "bcc"}, "Crystal structure").def("fcc"),
      Param::real("lattice_constant", Dimension::kLength,
                  "Zero-temperature lattice constant; the starting lattice of every MD stage")
          .require()
          .above(0),
  };
  return {{"eam_alloy", "Embedded-atom method, LAMMPS pair_style eam/alloy", fields},
          {"eam_fs", "Finnis-Sinclair EAM, LAMMPS pair_style eam/fs", fields}};
}

}  // namespace pbms::md
