#include "pbms/config/workflow.hpp"

namespace pbms::config {

Param dpd_potential_schema() {
  using units::Dimension;
  Param potential = Param::map(
      "potential",
      {Param::choice("style", {"morse", "lj_nm", "table", "sutton_chen"},
                     "Conservative force style of the DPD engine")
           .require()},
      "Conservative interaction of the mesoparticles; a potential file holds this same map");
  const Param cutoff = Param::real("cutoff", Dimension::kLength,
                                   "Beyond this distance the style contributes nothing")
                           .require()
                           .above(0);
  const Param shift = Param::boolean("shift",
                                     "Shift energies to zero at the cutoff (LAMMPS "
                                     "pair_modify shift yes)")
                          .def(false);
  potential.discriminated_by("style")
      .variant("morse",
               {Param::real("d0", Dimension::kEnergy, "Well depth D0").require().above(0),
                Param::real("alpha", Dimension::kNone, "Width alpha, 1/Å").require().above(0),
                Param::real("r0", Dimension::kLength, "Equilibrium distance r0").require().above(0),
                cutoff, shift},
               "D0 [exp(-2 alpha (r - r0)) - 2 exp(-alpha (r - r0))], as LAMMPS pair_style morse")
      .variant("lj_nm",
               {Param::real("e0", Dimension::kEnergy, "Well depth E0").require().above(0),
                Param::real("r0", Dimension::kLength, "Equilibrium distance r0").require().above(0),
                Param::real("n", Dimension::kNone, "Repulsive exponent").require().above(0),
                Param::real("m", Dimension::kNone, "Attractive exponent").require().above(0),
                cutoff, shift},
               "E0 / (n - m) [m (r0/r)^n - n (r0/r)^m], as LAMMPS pair_style nm/cut")
      .variant("table",
               {Param::file("file", "Rows r (Å), U (eV), F = -dU/dr (eV/Å)").require(),
                Param::real("cutoff", Dimension::kLength, "Cutoff; default the last row").above(0)},
               "Tabulated pair potential, cubic Hermite between rows")
      .variant("sutton_chen",
               {Param::real("epsilon", Dimension::kEnergy, "Energy scale").require().above(0),
                Param::real("a", Dimension::kLength, "Length scale").require().above(0),
                Param::real("n", Dimension::kNone, "Pair repulsion exponent").require().above(0),
                Param::real("m", Dimension::kNone, "Density exponent").require().above(0),
                Param::real("c", Dimension::kNone, "Embedding weight").require().above(0), cutoff},
               "eps [sum (a/r)^n - c sum_i sqrt(rho_i)], rho_i = sum_j (a/r_ij)^m");
  return potential;
}

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
  const Param density = Param::real("density", Dimension::kDensity, "Initial mass density")
                            .require()
                            .above(0)
                            .referable();
  const std::vector<Param> elastic_fields = {
      density,
      Param::real("youngs_modulus", Dimension::kPressure, "Young's modulus E")
          .require()
          .above(0)
          .referable(),
      Param::real("poisson_ratio", Dimension::kNone, "Poisson's ratio")
          .def(0.3)
          .above(-1.0)
          .at_most(0.49)
          .referable(),
  };
  // Von Mises yield with linear hardening, the same for both J2 styles.
  const std::vector<Param> hardening_fields = {
      Param::real("yield_stress", Dimension::kPressure, "Initial yield stress")
          .require()
          .above(0)
          .referable(),
      Param::real("hardening_modulus", Dimension::kPressure, "Linear isotropic hardening modulus H")
          .def(0.0)
          .at_least(0)
          .referable(),
  };
  std::vector<Param> j2_fields = elastic_fields;
  j2_fields.insert(j2_fields.end(), hardening_fields.begin(), hardening_fields.end());
  j2_fields.push_back(
      Param::real("zener_ratio", Dimension::kNone,
                  "Anisotropy 2 C44/(C11 - C12) of a cubic crystal with cube axes along x, y, z; "
                  "1 is isotropic. Other values keep E and nu as the [100] pull's and set C44 "
                  "to zener_ratio E/(2 (1 + nu)), e.g. a DPD crystal's "
                  "{from: <dpd_elastic stage>.zener_ratio}")
          .def(1.0)
          .above(0)
          .referable());
  const auto modulus = [](const char* name, const char* doc) {
    return Param::real(name, Dimension::kPressure, doc).require().referable();
  };
  std::vector<Param> cubic_j2_fields = {
      density,
      modulus("c11", "Cubic elastic constant C11, cube axes along x, y, z").above(0),
      modulus("c12", "Cubic elastic constant C12"),
      modulus("c44", "Cubic elastic constant C44").above(0),
  };
  cubic_j2_fields.insert(cubic_j2_fields.end(), hardening_fields.begin(), hardening_fields.end());
  const std::vector<Param> gas_fields = {
      density,
      Param::real("gamma", Dimension::kNone, "Ratio of specific heats").def(1.4).above(1.0),
  };
  const std::vector<Param> dpd_fields = {
      Param::real("mass", Dimension::kMass, "Mass of one mesoparticle").require().above(0),
      Param::real("lattice_constant", Dimension::kLength,
                  "Cubic cell edge of the mesoparticle fcc crystal")
          .require()
          .above(0),
      Param::integer("atoms_per_particle",
                     "Atoms one mesoparticle stands for; volumes per atom (isotherms, the MD "
                     "fit) divide by it")
          .def(8)
          .above(0),
      dpd_potential_schema().referable(),
      Param::file("potential_file",
                  "A YAML file holding the `potential` map (what the MD->DPD fit writes); "
                  "give this or `potential`"),
  };
  Param material =
      Param::map("material",
                 {Param::choice("kind",
                                {"eam_alloy", "eam_fs", "linear_elastic", "j2_plasticity",
                                 "cubic_j2_plasticity", "ideal_gas", "dpd_mesoparticle"},
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
      .variant("cubic_j2_plasticity", cubic_j2_fields,
               "MPM: von Mises plasticity on a cubic elastic crystal whose cube axes are x, y, "
               "z (cutting-plane return)")
      .variant("ideal_gas", gas_fields,
               "MPM: ideal gas P = (gamma - 1) rho e, e from the work of compression")
      .variant("dpd_mesoparticle", dpd_fields,
               "DPD: a coarse-grained particle (mass, crystal) and its conservative potential");
  return Param::map_of("materials", material, "Named materials that stages refer to");
}

}  // namespace pbms::config
