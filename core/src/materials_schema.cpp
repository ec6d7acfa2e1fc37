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
  // Continuum materials of the MPM engine. Numbers are in metal units
  // (bar, g/cm^3) unless a stage runs in `units: consistent`, where they
  // are plain numbers of one consistent system (the seed's 1-D bar).
  const Param density =
      Param::real("density", Dimension::kDensity, "Initial mass density").require().above(0);
  const std::vector<Param> elastic_fields = {
      density,
      Param::real("youngs_modulus", Dimension::kPressure, "Young's modulus E").require().above(0),
      Param::real("poisson_ratio", Dimension::kNone, "Poisson's ratio")
          .def(0.3)
          .above(-1.0)
          .at_most(0.49),
  };
  std::vector<Param> j2_fields = elastic_fields;
  j2_fields.push_back(
      Param::real("yield_stress", Dimension::kPressure, "Initial yield stress").require().above(0));
  j2_fields.push_back(
      Param::real("hardening_modulus", Dimension::kPressure, "Linear isotropic hardening modulus H")
          .def(0.0)
          .at_least(0));
  const std::vector<Param> gas_fields = {
      density,
      Param::real("gamma", Dimension::kNone, "Ratio of specific heats").def(1.4).above(1.0),
  };
  Param material = Param::map(
      "material",
      {Param::choice("kind",
                     {"eam_alloy", "eam_fs", "linear_elastic", "j2_plasticity", "ideal_gas"},
                     "Interaction model or constitutive model")
           .require()},
      "One material");
  material.discriminated_by("kind")
      .variant("eam_alloy", eam_fields, "Embedded-atom method, LAMMPS pair_style eam/alloy")
      .variant("eam_fs", eam_fields, "Finnis-Sinclair EAM, LAMMPS pair_style eam/fs")
      .variant("linear_elastic", elastic_fields,
               "MPM: isotropic linear elasticity, small strain with a Jaumann rate")
      .variant("j2_plasticity", j2_fields,
               "MPM: von Mises plasticity with linear isotropic hardening (radial return)")
      .variant("ideal_gas", gas_fields,
               "MPM: ideal gas P = (gamma - 1) rho e, e from the work of compression");
  return Param::map_of("materials", material, "Named materials that stages refer to");
}

}  // namespace pbms::config
