#include "pbms/coupling/concurrent_spec.hpp"

#include "pbms/geometry/region_yaml.hpp"

namespace pbms::coupling {

using config::OutputSpec;
using config::Param;
using units::Dimension;

namespace {

Param shared_grid() {
  return Param::map(
      "grid",
      {Param::real_list("origin", Dimension::kLength, "Lower corner; the box's on periodic axes")
           .require()
           .length(3, 3),
       Param::real("cell_size", Dimension::kLength, "Cell edge h, below the DPD cutoff (seed §2.4)")
           .require()
           .above(0),
       Param::int_list("cells", "Cells along x, y, z; the box's length over h on periodic axes")
           .require()
           .length(3, 3),
       Param::real("flip", Dimension::kNone, "FLIP/PIC blend of both solvers' velocity update")
           .def(1.0)
           .at_least(0)
           .at_most(1),
       Param::real("band_margin", Dimension::kLength,
                   "How far particles may travel from their start: the interface band's "
                   "nodes reach this much beyond where both bodies touch")
           .def(8.0)
           .at_least(0)},
      "The grid both solvers map to (one definition for both programs)");
}

Param region_entry() {
  return Param::map(
      "region",
      {Param::identifier("name", "Region name").require(),
       Param::choice("solver", {"dpd", "mpm"},
                     "Who advances the particles starting inside: dpd_driver (DPD particles) "
                     "or mpm_driver (elastic material points on the same sites)")
           .require(),
       geometry::region_param("region", "The part of the body").require()},
      "A part of the body and its solver; particles in no region stay DPD (a flyer)");
}

Param continuum() {
  return Param::map(
      "continuum",
      {Param::real("youngs_modulus", Dimension::kPressure,
                   "E of the MPM points: the DPD model's E<100> (dpd_elastic "
                   "youngs_modulus_100), or for a rod the slope of the same rod all DPD "
                   "(a thin rod of a pair potential is softer than its bulk crystal)")
           .require()
           .above(0)
           .referable(),
       Param::real("poisson_ratio", Dimension::kNone,
                   "ν of the MPM points: C12 / (C11 + C12) of the DPD model (dpd_elastic "
                   "poisson_ratio_100)")
           .require()
           .above(-1)
           .below(0.5)
           .referable(),
       Param::real("lattice_constant", Dimension::kLength,
                   "Lattice constant of the DPD crystal at the run's temperature (dpd_elastic "
                   "lattice_constant): each point's volume is a³/4; default the material's")
           .above(0)
           .referable(),
       Param::choice("gradient", {"plain", "ddmp"},
                     "The MPM points' gradients: plain shape-function gradients, or dual-domain "
                     "ones (DDMP; seed §7.3, Appendix 2), blended with the plain ones by "
                     "4 ξ (1 − ξ) per axis so that they vanish on cell faces")
           .def(std::string("plain"))},
      "The linear elastic material of the MPM points, derived from the DPD model");
}

Param wave() {
  const Param speed = Param::map(
      "speed",
      {Param::identifier("name", "Summary key suffix: wave_speed_<name>, front_speed_<name>")
           .require(),
       Param::identifier("near_slab", "Group nearer the impact face")
           .require()
           .names_entry_of({"bodies", "groups"}),
       Param::identifier("far_slab", "Group farther away, in the same solver's part")
           .require()
           .names_entry_of({"bodies", "groups"})},
      "A wave speed between two slabs of one solver's particles");
  return Param::map(
      "wave",
      {Param::choice("axis", {"x", "y", "z"}, "Direction of the wave").def(std::string("x")),
       Param::real("threshold", Dimension::kLength,
                   "A slab has moved when its centre of mass has moved this far")
           .def(0.25)
           .above(0),
       Param::real("smoothing", Dimension::kTime,
                   "Mid-amplitude arrival: a slab's velocity is a running mean over this time")
           .def(0.05)
           .above(0),
       Param::real("window", Dimension::kTime,
                   "Mid-amplitude arrival: the front's top is the largest smoothed velocity "
                   "within this time of the first motion")
           .def(0.1)
           .above(0),
       Param::list_of("speeds", speed, "Slab pairs").def(std::vector<std::string>{}),
       Param::map("opening",
                  {Param::identifier("dpd_plane", "The DPD lattice plane next to the interface")
                       .require()
                       .names_entry_of({"bodies", "groups"}),
                   Param::identifier("mpm_plane", "The MPM lattice plane next to the interface")
                       .require()
                       .names_entry_of({"bodies", "groups"})},
                  "The interface opening: how far the two planes have moved apart along the axis "
                  "since the start, each plane's particles counted whichever solver holds them")},
      "Wave speeds in each part and the interface opening");
}

}  // namespace

config::StageKindSpec concurrent_spec(std::vector<Param> body_params) {
  config::StageKindSpec s;
  s.kind = "concurrent";
  s.program = "dpd_driver";
  s.partners = {{"mpm_driver", "concurrent_mpm_part"}};
  s.checkpoints = true;
  s.doc =
      "One body, some regions DPD particles (dpd_driver) and some elastic MPM points "
      "(mpm_driver), on one grid, exchanging interface data rank to rank every step";
  s.material_kinds = {"dpd_mesoparticle"};
  for (auto& p : body_params) {
    if (p.name != "grid") s.params.push_back(std::move(p));
  }
  s.params.push_back(shared_grid().require());
  s.params.push_back(Param::list_of("regions", region_entry(),
                                    "The body's parts: each particle goes to the innermost "
                                    "region holding it (a region may nest in another, a core "
                                    "in a shell; others may touch but not overlap), particles "
                                    "in none stay DPD")
                         .require());
  s.params.push_back(
      Param::choice("interface", {"none", "seed", "momentum_conserving"},
                    "none: the grid alone joins the parts; seed: DPD particles take pair forces "
                    "from MPM points within the cutoff (s-15 to s-18); momentum_conserving: "
                    "and each acts back on its MPM point")
          .def(std::string("seed")));
  s.params.push_back(continuum().require());
  s.params.push_back(wave());
  s.params.push_back(Param::map(
      "tension",
      {Param::identifier("left_grip", "The rigid group pulled towards -axis")
           .require()
           .names_entry_of({"bodies", "groups"}),
       Param::identifier("right_grip", "The rigid group pulled towards +axis")
           .require()
           .names_entry_of({"bodies", "groups"}),
       Param::choice("axis", {"x", "y", "z"}, "Pulling direction").def(std::string("x")),
       Param::real("fit_strain", Dimension::kNone, "Upper end of the linear fit for E")
           .def(0.05)
           .above(0)},
      "A tension test between two rigid or frozen groups of either part: stress is the body's "
      "mean axial stress (DPD conservative virial plus MPM sum of sigma V, over the initial "
      "cross-section times the current length), strain the change of the grips' separation over "
      "the body's initial length; the grips' holding force over the initial cross-section is "
      "reported beside it"));
  s.params.push_back(Param::integer("profile_every", "Steps between displacement profiles; 0: none")
                         .def(0)
                         .at_least(0));
  s.outputs = {
      {"dpd_particles", OutputSpec::Shape::kScalar, "1", "DPD particles"},
      {"mpm_points", OutputSpec::Shape::kScalar, "1", "MPM points"},
      {"dpd_temperature", OutputSpec::Shape::kScalar, "K", "Kinetic temperature of the DPD part"},
      {"momentum_change", OutputSpec::Shape::kScalar, "1",
       "Largest change of the total momentum over the run, over M c (M the body's mass, c its "
       "bar speed)"},
      {"interface_opening", OutputSpec::Shape::kScalar, "Å",
       "How far the wave.opening planes moved apart since the start, at the end (negative: "
       "nearer)"},
      {"max_interface_opening", OutputSpec::Shape::kScalar, "Å",
       "The most they were apart (0 if never)"},
      {"max_interface_closing", OutputSpec::Shape::kScalar, "Å",
       "The most they came nearer (0 if never)"},
      {"steps_per_second", OutputSpec::Shape::kScalar, "1/s", "Speed of the run"},
      {"youngs_modulus", OutputSpec::Shape::kScalar, "GPa",
       "Slope of stress against strain up to tension.fit_strain"},
      {"max_stress", OutputSpec::Shape::kScalar, "GPa", "Largest mean axial stress (tension)"},
      {"tension_curve", OutputSpec::Shape::kTable, "",
       "Strain, mean axial stress and grip stress (tension)"},
      {"dpd_ledger", OutputSpec::Shape::kTable, "",
       "Every step, the DPD part's mass, momentum, kinetic, pair (potential_energy), internal "
       "and DPD-MPM interface pair energy"},
      {"mpm_ledger", OutputSpec::Shape::kTable, "",
       "Every step, the MPM part's mass, momentum, kinetic, stored and dissipated energy"},
      {"interface", OutputSpec::Shape::kTable, "", "The wave.opening planes' jump against time"},
      {"dpd_exchange", OutputSpec::Shape::kTable, "",
       "Per dpd_driver rank: messages, bytes sent and received, seconds packing and waiting, of "
       "the nodal sums (nodal_) and of the partners and their reactions (partner_); the "
       "dpd_exchange figures are left out when the body holds no DPD particle, the mpm_exchange "
       "ones when it holds no MPM point"},
      {"mpm_exchange", OutputSpec::Shape::kTable, "", "The same per mpm_driver rank"},
      {"nodal_sum_bytes_per_step", OutputSpec::Shape::kScalar, "1",
       "Bytes the DPD part sent in the nodal sums a step, all its ranks"},
      {"partner_bytes_per_step", OutputSpec::Shape::kScalar, "1",
       "Bytes the DPD part received as partners a step, all its ranks"},
      {"dpd_exchange_bytes_per_step", OutputSpec::Shape::kScalar, "1",
       "Bytes the DPD part sent and received across the programs a step, all its ranks"},
      {"dpd_exchange_messages_per_step", OutputSpec::Shape::kScalar, "1",
       "Messages the DPD part sent across the programs a step, all its ranks"},
      {"dpd_exchange_waiting_fraction", OutputSpec::Shape::kScalar, "1",
       "The longest any DPD rank waited for the other program, over the stepping time"},
      {"mpm_exchange_bytes_per_step", OutputSpec::Shape::kScalar, "1", "The same, MPM part"},
      {"mpm_exchange_messages_per_step", OutputSpec::Shape::kScalar, "1", "The same, MPM part"},
      {"mpm_exchange_waiting_fraction", OutputSpec::Shape::kScalar, "1", "The same, MPM part"},
  };
  return s;
}

}  // namespace pbms::coupling
