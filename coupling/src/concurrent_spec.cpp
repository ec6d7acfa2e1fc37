#include "pbms/coupling/concurrent_spec.hpp"

#include "pbms/coupling/neck_spec.hpp"

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
       Param::choice("move", {"step_start", "midpoint"},
                     "How both programs move their particles and points: midpoint, with the "
                     "grid velocity at the move's midpoint, the nodal sums of that second map "
                     "summed across the programs once more a step; step_start, with the grid "
                     "velocity at the step's start (MUSL: cheaper, but where particles share "
                     "nodes it drains their thermal motion, cooling the DPD part from 298 to "
                     "about 40 K in 6 ps; docs/concurrent.md)")
           .def(std::string("midpoint")),
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
                  "since the start, each plane's particles counted whichever solver holds them"),
       Param::map("baseline",
                  {Param::table("dpd", "The `dpd_slabs` table of the baseline stage"),
                   Param::table("mpm", "The `mpm_slabs` table of the baseline stage")},
                  "The slab histories of an earlier concurrent stage of the same body and start "
                  "that was not struck, whose noise this stage takes (`noise_of`): subtracted "
                  "from this stage's before any arrival is timed, which removes the body's own "
                  "drift and thermal motion; it must have run at least as many steps of the "
                  "same length")},
      "Wave speeds in each part and the interface opening");
}

// The pressure medium of the seed's chapter 6: ideal-gas MPM points of
// mpm_driver filling the box around the DPD bodies, touching them only
// through the grid nodes both map to.
Param gas() {
  return Param::map(
      "gas",
      {Param::real("spacing", Dimension::kLength,
                   "Edge of the gas points' simple cubic lattice (the seed: a_cg)")
           .require()
           .above(0),
       Param::real_list("origin", Dimension::kLength,
                        "One site of the lattice; default the box's lower corner")
           .length(3, 3),
       Param::real("density", Dimension::kDensity,
                   "The gas's mass density; each point weighs density x spacing³")
           .require()
           .above(0),
       Param::real("pressure", Dimension::kPressure,
                   "Target pressure: each point's internal energy is set so that "
                   "(γ − 1) ρ e is this")
           .require()
           .at_least(0)
           .referable(),
       Param::real("gamma", Dimension::kNone, "Ratio of specific heats").def(1.4).above(1),
       Param::real("clearance", Dimension::kLength,
                   "Sites closer than this to a particle of the body are left empty; default "
                   "0.75 spacing, which empties the sites on a body's surface planes")
           .above(0),
       Param::real("probe_distance", Dimension::kLength,
                   "The gas pressure reached is the mean over the gas points at least this far "
                   "from every particle of the body at the start (away from the solid)")
           .def(15.0)
           .at_least(0),
       Param::real("settle_time", Dimension::kTime,
                   "gas_pressure and gas_pressure_on_walls are the means of the samples from "
                   "this time on")
           .def(0.0)
           .at_least(0),
       Param::real("flip", Dimension::kNone,
                   "The gas points' own FLIP/PIC blend: at one point per cell an inviscid gas "
                   "under FLIP alone grows velocity modes the grid cannot see; some PIC damps "
                   "them (the body keeps grid.flip)")
           .def(0.95)
           .at_least(0)
           .at_most(1),
       Param::choice("density_from", {"grid", "points"},
                     "grid: each gas point's density is the gas's nodal mass over the nodal "
                     "volume the body's mass does not fill (at the body's crystal density), "
                     "every step; points: integrated along each point's path from its velocity "
                     "gradient, as MPM does for solids")
           .def(std::string("grid")),
       Param::real("density_time", Dimension::kTime,
                   "density_from grid: each point's density relaxes to the grid's over this "
                   "time; shorter than the gas's sound crossing a cell it pumps energy into "
                   "the sound (the grid's density acts a step late)")
           .def(2.0)
           .above(0),
       Param::real("heat_bath_time", Dimension::kTime,
                   "The gas's specific internal energy relaxes to its starting value over this "
                   "time: the gas keeps the temperature it started at, as one in contact with "
                   "the thermostatted body would, instead of heating up on the body's thermal "
                   "motion; 0 leaves it adiabatic")
           .def(1.0)
           .at_least(0),
       Param::real("ramp_time", Dimension::kTime,
                   "The gas's pressure rises from zero to `pressure` over this time: its "
                   "specific internal energy starts at zero and the heat bath's target rises "
                   "linearly to the target's. A body set at once into a gas of several GPa is "
                   "struck by it (at 5 GPa the cube of configs/inclusion_in_gas.yaml reached "
                   "590 K within 0.3 ps); 0 sets the full pressure at the start. Needs "
                   "heat_bath_time > 0")
           .def(0.0)
           .at_least(0),
       Param::boolean("walls",
                      "The box's non-periodic faces are walls: the grid nodes on "
                      "them keep no normal velocity")
           .def(true),
       Param::choice("contact", {"shared_velocity", "frictionless"},
                     "How the gas and the body move at a node both reach. shared_velocity: "
                     "one velocity, their nodal sums added, so that a gas point among the "
                     "body's nodes moves with the body (gas caught between two bodies "
                     "stays there). frictionless: each its own velocity, taking a common "
                     "one along the surface normal only where they approach (Bardenhagen "
                     "et al. 2000), so that the gas slides along the body and out of a "
                     "closing gap. frictionless needs the body all DPD (no MPM region)")
           .def(std::string("shared_velocity"))},
      "Ideal-gas MPM points (P = (γ − 1) ρ e, seed eq. 6.1) filling the box outside the body, "
      "advanced by mpm_driver");
}

// How big a body is: its edges from its outermost lattice planes, along
// its own axes as it turns.
Param volume() {
  return Param::map(
      "volume",
      {Param::identifier("group", "The body (a group or body name) whose volume is measured")
           .require()
           .names_entry_of({"bodies", "groups"}),
       Param::real("reference", Dimension::kNone,
                   "V0 in Å³ (for instance another stage's body_volume); default the volume "
                   "at the start")
           .above(0)
           .referable()},
      "A block's volume as the product of its three edges along its own axes: each particle's "
      "lattice site is fitted at the start, each sample finds the block's turn (the rotation "
      "that best carries the sites onto the particles), and an edge is the distance between "
      "the mean positions of the two outermost whole lattice planes along that turned axis, "
      "times (n + 1)/n for n plane spacings between them");
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
                         .def(std::vector<std::string>{}));
  s.params.push_back(
      Param::choice("interface", {"none", "seed", "momentum_conserving"},
                    "none: the grid alone joins the parts; seed: DPD particles take pair forces "
                    "from MPM points within the cutoff (s-15 to s-18); momentum_conserving: "
                    "and each acts back on its MPM point")
          .def(std::string("seed")));
  s.params.push_back(
      Param::map(
          "ghost_force_correction",
          {Param::real("average_time", Dimension::kTime,
                       "The reference reactions are the mean over the stage's first this much "
                       "(at least one step); 0: the first step's, the correction at 0 K. At a "
                       "temperature one step holds the particles' thermal forces too")
               .def(0.0)
               .at_least(0),
           Param::identifier("from_stage",
                             "Apply from the first step the dead loads an earlier concurrent "
                             "stage of the same body measured (its ghost_forces.h5), instead "
                             "of measuring: a body measured at rest, then loaded or strained")
               .earlier_stage({"concurrent"})},
          "Subtract from each MPM point the pair reaction it takes in the reference state (the "
          "quasicontinuum's ghost-force correction as a dead load): at rest the interface then "
          "pushes no point, where without it the first MPM plane is pushed and the second "
          "pulled by the DPD neighbours whose MPM counterparts the continuum lacks "
          "(docs/concurrent.md). The stage writes the dead loads to ghost_forces.h5")
          .only_when("interface", "momentum_conserving"));
  s.params.push_back(
      Param::real_list("initial_strain", Dimension::kNone,
                       "The body starts uniformly strained by this much along x, y and z: "
                       "positions scaled about the box's lower corner (give a periodic axis "
                       "its strained length), the MPM points carrying the stress of that strain "
                       "(λ tr ε + 2 μ ε of the continuum). A ghost_force_correction must then come "
                       "from_stage: its reference state is the unstrained body")
          .def(std::vector<double>{0.0, 0.0, 0.0})
          .length(3, 3));
  s.params.push_back(continuum());
  s.params.push_back(gas());
  s.params.push_back(Param::map(
      "thermostat",
      {Param::real("temperature", Dimension::kTemperature, "Target temperature of the DPD part")
           .require()
           .above(0),
       Param::real("tau", Dimension::kTime,
                   "Coupling time. The default holds a grid crystal at h = a/2 1.3 % below its "
                   "temperature, where 0.5 ps held it 6 % below (docs/dpd-driver.md)")
           .def(0.1)
           .above(0)},
      "Berendsen rescaling of the DPD part's free particles about their mean velocity after "
      "each step (momentum kept). The grid step drains their thermal motion into the grid "
      "(and into a gas sharing its nodes) far faster than the pair thermostat (gamma) gives "
      "it back; this holds the body at its temperature"));
  s.params.push_back(volume());
  s.params.push_back(necks_param());
  s.params.push_back(neck_stable_time_param());
  s.params.push_back(
      Param::list_of(
          "rods",
          Param::map(
              "rod",
              {Param::identifier("name", "Key suffix: rod_<name>, rod_deflection_<name>").require(),
               Param::identifier("group", "The rod (a body or group)")
                   .require()
                   .names_entry_of({"bodies", "groups"}),
               Param::choice("axis", {"x", "y", "z"}, "The rod's axis").def(std::string("z"))},
              "A rod whose bend is followed"),
          "Rods that spheres sinter to (seed §6.4): the bend is the largest distance of the "
          "rod's centre line (its slabs' centroids, a thick along the axis) from the chord "
          "between its ends")
          .def(std::vector<std::string>{}));
  s.params.push_back(wave());
  s.params.push_back(
      Param::identifier("noise_of",
                        "Draw the DPD part's pair noise and any velocities as this earlier "
                        "concurrent stage did (the run seed mixed with its name), so that a stage "
                        "and its wave.baseline share their thermal noise")
          .earlier_stage({"concurrent"}));
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
      "mean axial stress (DPD conservative virial plus MPM sum of sigma V, over the nominal "
      "cross-section times the current length; the nominal cross-section is the body's sites "
      "times a^3/4 over its initial length, which thermal excursions of the outermost sites do "
      "not widen), strain the change of the grips' separation over the body's initial length; "
      "the grips' holding force over the nominal cross-section is reported beside it"));
  s.params.push_back(Param::integer("profile_every", "Steps between displacement profiles; 0: none")
                         .def(0)
                         .at_least(0));
  s.outputs = {
      {"dpd_particles", OutputSpec::Shape::kScalar, "1", "DPD particles"},
      {"mpm_points", OutputSpec::Shape::kScalar, "1", "MPM points of the body"},
      {"gas_points", OutputSpec::Shape::kScalar, "1", "Gas points (gas)"},
      {"gas_pressure", OutputSpec::Shape::kScalar, "GPa",
       "Mean pressure of the gas points away from the body, over the samples from "
       "gas.settle_time on (gas)"},
      {"gas_pressure_target", OutputSpec::Shape::kScalar, "GPa", "gas.pressure (gas)"},
      {"gas_pressure_error", OutputSpec::Shape::kScalar, "1",
       "gas_pressure over its target, minus one (gas)"},
      {"gas_pressure_on_walls", OutputSpec::Shape::kScalar, "GPa",
       "The walls' mean pressure (their inward push over time and area: a manometer's "
       "reading, in which no point's state enters) over the samples from gas.settle_time on "
       "(gas, walls)"},
      {"gas_pressure_on_walls_error", OutputSpec::Shape::kScalar, "1",
       "gas_pressure_on_walls over its target, minus one (gas, walls)"},
      {"gas_pressure_series", OutputSpec::Shape::kTable, "",
       "Each sample: the gas pressure away from the body and over every gas point, and the "
       "walls' mean pressure since the sample before (gas)"},
      {"wall_impulse", OutputSpec::Shape::kScalar, "g/mol*Å/ps",
       "Magnitude of the momentum the walls took from the gas over the run (gas)"},
      {"rod_<name>", OutputSpec::Shape::kTable, "", "Each sample: the rod's bend"},
      {"rod_deflection_<name>", OutputSpec::Shape::kScalar, "Å",
       "The rod's largest bend over the run (its largest lateral deflection)"},
      {"rod_bend_initial_<name>", OutputSpec::Shape::kScalar, "Å",
       "The bend at the start: the straight rod's slab scatter"},
      {"body_volume", OutputSpec::Shape::kScalar, "Å^3",
       "The volume.group's block volume, mean over the last half of the samples (volume)"},
      {"body_edges", OutputSpec::Shape::kTable, "",
       "Each sample: the block's three edges along its own axes, its volume and its turn "
       "from the box's axes in degrees (volume)"},
      {"volume_ratio", OutputSpec::Shape::kScalar, "1",
       "body_volume over volume.reference, or over the volume at the start (volume)"},
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
      {"dpd_slabs", OutputSpec::Shape::kTable, "",
       "Every step, the displacement along the wave's axis of each wave.speeds slab the DPD part "
       "holds and, with a wave.baseline, the same less the baseline's (<slab>_response)"},
      {"mpm_slabs", OutputSpec::Shape::kTable, "", "The same, MPM part"},
      {"wave_speed_<name>", OutputSpec::Shape::kScalar, "m/s",
       "Distance between the speed's slabs over the difference of their first motions "
       "(wave.threshold; of their responses, with a wave.baseline)"},
      {"front_speed_<name>", OutputSpec::Shape::kScalar, "m/s",
       "The same, half way up the slabs' velocity rise"},
      {"baseline_residual_<name>", OutputSpec::Shape::kScalar, "Å",
       "The far slab's largest response before the near slab's first motion: how well the "
       "baseline cancels the body's own motion (wave.baseline)"},
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
  for (auto& o : neck_outputs()) s.outputs.push_back(std::move(o));
  return s;
}

}  // namespace pbms::coupling
