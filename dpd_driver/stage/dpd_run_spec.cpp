#include "dpd_run.hpp"
#include "pbms/analysis/tension_test.hpp"
#include "pbms/geometry/region_yaml.hpp"

namespace pbms::dpd {

using config::OutputSpec;
using config::Param;
using geometry::region_param;
using units::Dimension;

std::vector<Param> dpd_stage_params() {
  const Param box =
      Param::map("box",
                 {Param::real_list("lo", Dimension::kLength, "Lower corner").require().length(3, 3),
                  Param::real_list("hi", Dimension::kLength, "Upper corner").require().length(3, 3),
                  Param::list_of("periodic", Param::choice("axis", {"x", "y", "z"}, "An axis"),
                                 "Periodic axes; on the others particles are free (surfaces)")
                      .def(std::vector<std::string>{})
                      .length(0, 3)},
                 "The simulation box: periodic cell, and the span the ranks split");
  const Param body = Param::map(
      "body",
      {Param::identifier("name", "Body name; also a group of its particles").require(),
       region_param("region", "Region the body's fcc lattice fills").require(),
       Param::real_list("lattice_origin", Dimension::kLength,
                        "A lattice site; shift it to place a body apart from another")
           .def(std::vector<double>{0.0, 0.0, 0.0})
           .length(3, 3)},
      "A crystal of the stage's material: fcc sites of its lattice_constant inside a region");
  const Param initial =
      Param::map("initial",
                 {Param::identifier("from_stage",
                                    "An earlier dpd_equilibrate or dpd_run stage's final state")
                      .earlier_stage({"dpd_run", "dpd_equilibrate"}),
                  Param::file("h5md", "The last frame of an H5MD file"),
                  Param::file("lammps_data", "A LAMMPS data file (atom_style atomic)")},
                 "Start from an existing state instead of `bodies`")
          .exactly_one_key();
  const Param group = Param::map(
      "group",
      {Param::identifier("name", "Group name").require(),
       region_param("region", "The group holds the particles inside at the start").require()},
      "A named set of particles");
  Param motion = Param::map(
      "motion",
      {Param::identifier("group", "Group or body").require(),
       Param::choice("kind", {"rigid", "rigid_body", "frozen", "velocity"}, "What is prescribed")
           .require()},
      "A group behaviour");
  motion.discriminated_by("kind")
      .variant("rigid",
               {Param::real_list("velocity", Dimension::kVelocity, "Constant velocity")
                    .require()
                    .length(3, 3),
                Param::real("ramp_time", Dimension::kTime,
                            "Reach the velocity linearly over this time from rest (0: at once). "
                            "About one wave transit of the body loads it without the stress "
                            "step a grip at full speed sends through it")
                    .def(0.0)
                    .at_least(0)},
               "Moves rigidly at a constant velocity (a grip, a driven piston)")
      .variant("rigid_body",
               {Param::real_list("velocity", Dimension::kVelocity, "Initial velocity")
                    .require()
                    .length(3, 3)},
               "A free rigid body launched at a velocity, slowed or sped by the net force on "
               "it (a flyer)")
      .variant("frozen", {}, "Held in place")
      .variant("velocity",
               {Param::real_list("velocity", Dimension::kVelocity, "Added to the thermal velocity")
                    .require()
                    .length(3, 3)},
               "An initial velocity; the particles move freely afterwards");
  Param probe =
      Param::map("probe",
                 {Param::identifier("name", "Column prefix in the probes table").require(),
                  Param::choice("kind",
                                {"temperature", "pressure", "energy", "momentum",
                                 "slab_displacement", "group_force", "group_extent"},
                                "What is sampled")
                      .require()},
                 "A quantity sampled every sample_every steps");
  probe.discriminated_by("kind")
      .variant("temperature", {}, "Kinetic temperature of all particles")
      .variant("pressure", {},
               "Pressure tensor (kinetic + conservative virial) over the box volume, and its "
               "trace")
      .variant("energy", {}, "Kinetic, potential, internal (DPDE) and total energy")
      .variant("momentum", {}, "Total momentum")
      .variant("slab_displacement", {Param::identifier("group", "Group").require()},
               "Centre-of-mass displacement of a group from the stage start")
      .variant("group_force", {Param::identifier("group", "Group").require()},
               "Total force on a group's particles (stress = force / area)")
      .variant("group_extent",
               {Param::identifier("group", "Group").require(),
                Param::choice("axis", {"x", "y", "z"}, "Axis").require()},
               "Largest minus smallest coordinate of a group (V/V0, strain)");
  return {
      Param::identifier("material", "A dpd_mesoparticle material").require().material(),
      box,
      Param::list_of("bodies", body, "Lattice-filled bodies").def(std::vector<std::string>{}),
      initial,
      Param::list_of("groups", group, "Named groups").def(std::vector<std::string>{}),
      Param::list_of("motion", motion, "Group behaviours").def(std::vector<std::string>{}),
      Param::real("temperature", Dimension::kTemperature,
                  "Maxwell-Boltzmann velocities at this temperature for the free particles; 0 "
                  "keeps the state's velocities (a file's or stage's) or starts at rest")
          .def(0.0)
          .at_least(0),
      Param::choice("scheme", {"velocity_verlet", "nve", "shardlow", "shardlow_dpde"},
                    "velocity_verlet: isothermal DPD in one VV step; nve: conservative forces "
                    "only; shardlow / shardlow_dpde: S1 splitting, isothermal or "
                    "energy-conserving. All run on any rank count with the same result")
          .def(std::string("velocity_verlet")),
      Param::real("gamma", Dimension::kNone, "DPD friction coefficient, g/mol/ps")
          .def(0.2)
          .at_least(0),
      Param::real("dpd_cutoff", Dimension::kLength, "Range of the DPD weight functions")
          .def(10.0)
          .above(0),
      Param::choice("noise", {"uniform", "gaussian"},
                    "Distribution of the pair random number θ (zero mean, unit variance): "
                    "uniform, √3(2u − 1) (Groot & Warren 1997, HOOMD-blue; a full DPD step "
                    "costs about 25 % less), or gaussian (as LAMMPS pair dpd). Only the "
                    "first two moments enter the dynamics, so both sample the same "
                    "ensemble")
          .def(std::string("uniform")),
      Param::real("bath_temperature", Dimension::kTemperature,
                  "Temperature of the DPD thermostat (isothermal schemes); default `temperature`")
          .at_least(0),
      Param::real("heat_capacity", Dimension::kNone,
                  "DPDE: heat capacity C_v of one mesoparticle, in k_B (e.g. 3 x atoms "
                  "inside, minus 3)")
          .def(21.0)
          .above(0),
      Param::map(
          "grid",
          {Param::real("cell_size", Dimension::kLength,
                       "Cell edge h; below dpd_cutoff (seed §2.4), and a whole number of cells "
                       "along each periodic axis")
               .require()
               .above(0),
           Param::real("flip", Dimension::kNone, "FLIP/PIC blend of the particle velocity update")
               .def(1.0)
               .at_least(0)
               .at_most(1)},
          "The DPD/MPM-grid model (seed §2.4, §5.2): pair forces mapped to an MPM grid, "
          "particles moved with the grid velocity, instead of velocity Verlet. Rigid, frozen "
          "and rigid_body groups move rigidly on the grid. On several ranks the ranks split "
          "the grid's cells (each box at least cutoff + skin thick where it passes ghosts on). "
          "Scheme velocity_verlet or nve"),
      Param::real("time_step", Dimension::kTime, "Time step").def(0.01).above(0),
      Param::integer("steps", "Time steps; 0 writes the initial forces and energies")
          .require()
          .at_least(0),
      Param::real("skin", Dimension::kLength, "Neighbour list skin").def(1.0).at_least(0),
      Param::integer("sample_every", "Steps between probe samples").def(10).above(0),
      Param::list_of("probes", probe, "Sampled quantities").def(std::vector<std::string>{}),
      Param::integer("particles_every", "Steps between H5MD frames; 0 writes the last only")
          .def(0)
          .at_least(0),
      Param::boolean("write_forces", "Add forces to the H5MD frames").def(false),
      Param::boolean("write_internal_energy", "Add DPDE internal energies to the H5MD frames")
          .def(false),
  };
}

namespace {

std::vector<OutputSpec> common_outputs() {
  return {
      {"steps", OutputSpec::Shape::kScalar, "1", "Time steps taken"},
      {"particles", OutputSpec::Shape::kScalar, "1", "Mesoparticles"},
      {"temperature", OutputSpec::Shape::kScalar, "K", "Kinetic temperature at the end"},
      {"mean_temperature", OutputSpec::Shape::kScalar, "K", "Mean over the samples after step 0"},
      {"potential_energy", OutputSpec::Shape::kScalar, "eV", "Potential energy at the end"},
      {"total_energy", OutputSpec::Shape::kScalar, "eV",
       "Kinetic + potential + internal energy at the end"},
      {"energy_drift", OutputSpec::Shape::kScalar, "1",
       "(E_end - E_0) / |E_0| of the total energy (with an energy probe)"},
      {"pressure", OutputSpec::Shape::kScalar, "bar", "Pressure at the end (box volume)"},
      {"steps_per_second", OutputSpec::Shape::kScalar, "1/s", "Speed of the run"},
      {"probes", OutputSpec::Shape::kTable, "", "Probe samples"},
  };
}

}  // namespace

config::StageKindSpec DpdRunStage::spec() {
  config::StageKindSpec s;
  s.kind = "dpd_run";
  s.program = "dpd_driver";
  s.doc =
      "DPD or DPDE run of mesoparticles: free, impact (wave speed) or tension (Young's "
      "modulus)";
  s.material_kinds = {"dpd_mesoparticle"};
  s.params = dpd_stage_params();
  s.params.push_back(
      Param::choice("mode", {"free", "impact", "tension"},
                    "free: no analysis; impact: wave speed from two slabs' first motion; "
                    "tension: Young's modulus from the virial stress against the strain")
          .def(std::string("free")));
  s.params.push_back(Param::map(
      "impact",
      {Param::identifier("near_slab", "Group nearer the impact face").require(),
       Param::identifier("far_slab", "Group farther from the impact face").require(),
       Param::choice("axis", {"x", "y", "z"}, "Direction of the wave").def(std::string("x")),
       Param::real("threshold", Dimension::kLength,
                   "A slab has moved when its centre of mass has moved this far along the axis")
           .def(0.25)
           .above(0),
       Param::choice("arrival", {"first_motion", "mid_amplitude"},
                     "What wave_speed times: first_motion, the threshold's crossing (a foot "
                     "that fires part-way up the front); mid_amplitude, half way up the slab's "
                     "velocity rise, the shock speed that a Rayleigh line predicts")
           .def(std::string("first_motion")),
       Param::real("smoothing", Dimension::kTime,
                   "Mid-amplitude: the slab velocity is a running mean over this time")
           .def(0.05)
           .above(0),
       Param::real("window", Dimension::kTime,
                   "Mid-amplitude: the front's top is the largest smoothed velocity within "
                   "this time of the first motion")
           .def(0.1)
           .above(0)},
      "mode: impact"));
  std::vector<Param> tension = {
      Param::identifier("specimen", "The rod: a body or group, grips included").require(),
      Param::choice("axis", {"x", "y", "z"}, "Pulling direction").def(std::string("x")),
      Param::real("area", Dimension::kNone, "Cross-section, Å^2 (default: from the extents)")
          .above(0),
      Param::map("grips",
                 {Param::identifier("left", "The grip group at the low end").require(),
                  Param::identifier("right", "The grip group at the high end").require()},
                 "The grip groups, whose pull over the initial cross-section gives "
                 "grip_youngs_modulus")};
  for (auto& q : analysis::TensionTest::params()) tension.push_back(std::move(q));
  s.params.push_back(Param::map(
      "tension", std::move(tension),
      "mode: tension. Stress is the specimen's mean conservative virial stress, strain its "
      "elongation over its length"));
  s.outputs = common_outputs();
  s.outputs.push_back({"grip_youngs_modulus", OutputSpec::Shape::kScalar, "GPa",
                       "Slope of the grips' stress (the rod's pull on them: the pair force on the "
                       "left grip less that on the right, halved, over the initial "
                       "cross-section) against the strain, over youngs_modulus's window "
                       "(tension, with grips)"});
  s.outputs.push_back({"wave_speed", OutputSpec::Shape::kScalar, "m/s",
                       "Distance between the slabs over the difference of their arrival times, "
                       "by impact.arrival (impact)"});
  s.outputs.push_back({"first_motion_speed", OutputSpec::Shape::kScalar, "m/s",
                       "Distance between the slabs over the difference of their first-motion "
                       "times (impact)"});
  s.outputs.push_back({"mid_amplitude_speed", OutputSpec::Shape::kScalar, "m/s",
                       "Distance between the slabs over the difference of their mid-amplitude "
                       "arrival times (impact)"});
  s.outputs.push_back({"front_near", OutputSpec::Shape::kScalar, "ps",
                       "Mid-amplitude arrival time at the near slab (impact)"});
  s.outputs.push_back({"front_far", OutputSpec::Shape::kScalar, "ps",
                       "Mid-amplitude arrival time at the far slab (impact)"});
  s.outputs.push_back({"front_velocity_near", OutputSpec::Shape::kScalar, "m/s",
                       "The near slab's velocity at the top of the front (impact)"});
  s.outputs.push_back({"front_velocity_far", OutputSpec::Shape::kScalar, "m/s",
                       "The far slab's velocity at the top of the front (impact)"});
  s.outputs.push_back({"particle_velocity", OutputSpec::Shape::kScalar, "m/s",
                       "Mean of the two slabs' front velocities: the particle velocity behind "
                       "the front between them (impact)"});
  s.outputs.push_back({"first_motion_near", OutputSpec::Shape::kScalar, "ps",
                       "First-motion time of the near slab (impact)"});
  s.outputs.push_back({"first_motion_far", OutputSpec::Shape::kScalar, "ps",
                       "First-motion time of the far slab (impact)"});
  for (auto& o : analysis::TensionTest::outputs("tension")) s.outputs.push_back(std::move(o));
  return s;
}

config::StageKindSpec DpdEquilibrateStage::spec() {
  config::StageKindSpec s;
  s.kind = "dpd_equilibrate";
  s.program = "dpd_driver";
  s.doc = "DPD run with a Berendsen thermostat, for a later stage to start from";
  s.material_kinds = {"dpd_mesoparticle"};
  s.params = dpd_stage_params();
  s.params.push_back(
      Param::real("target_temperature", Dimension::kTemperature, "Berendsen target temperature")
          .require()
          .at_least(0));
  s.params.push_back(
      Param::real("tau", Dimension::kTime, "Berendsen coupling time").def(0.1).above(0));
  s.outputs = common_outputs();
  return s;
}

}  // namespace pbms::dpd
