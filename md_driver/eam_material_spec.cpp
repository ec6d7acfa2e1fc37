#include "eam_material_spec.hpp"

namespace pbms::md {

std::vector<config::MaterialKindSpec> eam_material_kinds() {
  using config::Param;
  using units::Dimension;
  // What every kind gives besides its potential.
  const std::vector<Param> crystal = {
      Param::string("element", "Element name as listed in the potential file").def("Cu"),
      Param::real("mass", Dimension::kMass, "Atomic mass").require().above(0),
      Param::choice("lattice", {"fcc", "bcc"}, "Crystal structure").def("fcc"),
      Param::real("lattice_constant", Dimension::kLength,
                  "Zero-temperature lattice constant; the starting lattice of every MD stage")
          .require()
          .above(0),
  };
  std::vector<Param> fields = {
      Param::file("potential", "Potential file in LAMMPS setfl format").require()};
  fields.insert(fields.end(), crystal.begin(), crystal.end());
  std::vector<Param> sutton_chen = {
      Param::real("epsilon", Dimension::kEnergy, "Energy scale").require().above(0),
      Param::real("a", Dimension::kLength, "Length scale").require().above(0),
      Param::real("c", Dimension::kNone, "Weight of the embedding term").require().above(0),
      Param::real("n", Dimension::kNone, "Exponent of the pair repulsion").require().above(0),
      Param::real("m", Dimension::kNone, "Exponent of the density").require().above(0),
      Param::real("cutoff", Dimension::kLength,
                  "Range of the table; the sums of Sutton and Chen run over all neighbours, "
                  "so take several shells")
          .require()
          .above(0),
      Param::real("smoothing", Dimension::kLength,
                  "Width below the cutoff over which the pair energy and density are switched "
                  "smoothly to zero")
          .def(0.5)
          .at_least(0),
  };
  sutton_chen.insert(sutton_chen.end(), crystal.begin(), crystal.end());
  return {{"eam_alloy", "Embedded-atom method, LAMMPS pair_style eam/alloy", fields},
          {"eam_fs", "Finnis-Sinclair EAM, LAMMPS pair_style eam/fs", fields},
          {"sutton_chen",
           "Sutton-Chen many-body potential (the seed's force field), tabulated by md_driver as "
           "a LAMMPS setfl file for pair_style eam/alloy",
           sutton_chen}};
}

}  // namespace pbms::md
