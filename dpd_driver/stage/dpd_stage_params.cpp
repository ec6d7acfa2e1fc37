#include "dpd_stage_params.hpp"

#include "kernels/pair_style_registry.hpp"
#include "pbms/geometry/region_yaml.hpp"

namespace pbms::dpd {

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
                 "The simulation box: periodic cell, and the span the ranks split")
          .bounds("lo", "hi");
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
                  Param::file("lammps_data", "A LAMMPS data file (atom_style atomic)"),
                  Param::list_of(
                      "pieces",
                      Param::map("piece",
                                 {Param::identifier("from_stage",
                                                    "An earlier dpd_equilibrate or dpd_run stage's "
                                                    "final state")
                                      .require()
                                      .earlier_stage({"dpd_run", "dpd_equilibrate"}),
                                  Param::real_list("shift", Dimension::kLength,
                                                   "Moves the state by this much")
                                      .def(std::vector<double>{0.0, 0.0, 0.0})
                                      .length(3, 3)},
                                 "One earlier state, moved into place"),
                      "Several earlier states, each moved into place, as one set of bodies "
                      "(the seed's sintering assemblies: spheres and a rod, each "
                      "equilibrated alone); ids run on from piece to piece")
                      .length(1, 64)},
                 "Start from an existing state instead of `bodies`")
          .exactly_one_key()
          .not_with("bodies");
  const Param group = Param::map(
      "group",
      {Param::identifier("name", "Group name").require(),
       region_param("region", "The group holds the particles inside at the start").require()},
      "A named set of particles");
  Param motion = Param::map(
      "motion",
      {Param::identifier("group", "Group or body").require().names_entry_of({"bodies", "groups"}),
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
      .variant("slab_displacement",
               {Param::identifier("group", "Group").require().names_entry_of({"bodies", "groups"})},
               "Centre-of-mass displacement of a group from the stage start")
      .variant("group_force",
               {Param::identifier("group", "Group").require().names_entry_of({"bodies", "groups"})},
               "Total force on a group's particles (stress = force / area)")
      .variant("group_extent",
               {Param::identifier("group", "Group").require().names_entry_of({"bodies", "groups"}),
                Param::choice("axis", {"x", "y", "z"}, "Axis").require()},
               "Largest minus smallest coordinate of a group (V/V0, strain)");
  return {
      Param::identifier("material", "A dpd_mesoparticle material").require().material(),
      box,
      Param::list_of("bodies", body, "Lattice-filled bodies")
          .def(std::vector<std::string>{})
          .with_stage_names(),
      initial,
      Param::list_of("groups", group, "Named groups")
          .def(std::vector<std::string>{})
          .with_stage_names(),
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
               .at_most(1),
           Param::choice("move", {"midpoint", "step_start"},
                         "The grid velocity the particles move with. midpoint: their new "
                         "momentum mapped to the grid again at the midpoint half the move "
                         "predicts, the move made from the step's start (second order; a "
                         "crystal whose particles share nodes keeps its energy as velocity "
                         "Verlet does; one more grid pass). step_start: the updated nodal "
                         "velocity at the step's start (MUSL, as the seed; first order, it loses "
                         "a third of a crystal's energy in 10 ps at h = a/2)")
               .def(std::string("midpoint"))},
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

Vec3 vec3(const YAML::Node& n) {
  const auto v = n.as<std::vector<double>>();
  return {v.at(0), v.at(1), v.at(2)};
}

OrthogonalBox box_from_yaml(const YAML::Node& b) {
  OrthogonalBox box;
  box.lo = vec3(b["lo"]);
  box.hi = vec3(b["hi"]);
  box.periodic = {false, false, false};
  for (const auto& a : b["periodic"]) box.periodic[axis_index(a.as<std::string>())] = true;
  return box;
}

DpdStageParams::Initial initial_from_yaml(const YAML::Node& n) {
  DpdStageParams::Initial i;
  i.keys = n.size();
  if (n["from_stage"]) i.from_stage = n["from_stage"].as<std::string>();
  if (n["h5md"]) i.h5md = n["h5md"].as<std::string>();
  if (n["lammps_data"]) i.lammps_data = n["lammps_data"].as<std::string>();
  for (const auto& piece : n["pieces"]) {
    i.pieces.push_back({piece["from_stage"].as<std::string>(), vec3(piece["shift"])});
  }
  return i;
}

DpdStageParams::Motion motion_from_yaml(const YAML::Node& m) {
  DpdStageParams::Motion mo;
  mo.group = m["group"].as<std::string>();
  mo.kind = m["kind"].as<std::string>();
  if (mo.kind != "frozen") mo.velocity = vec3(m["velocity"]);
  if (mo.kind == "rigid") mo.ramp_time = m["ramp_time"].as<double>(0.0);
  return mo;
}

DpdProbeSpec probe_from_yaml(const YAML::Node& p) {
  DpdProbeSpec s;
  s.name = p["name"].as<std::string>();
  s.kind = p["kind"].as<std::string>();
  if (p["group"]) s.group = p["group"].as<std::string>();
  if (p["axis"]) s.axis = axis_index(p["axis"].as<std::string>());
  return s;
}

}  // namespace

config::MaterialKindSpec MesoparticleMaterial::spec() {
  return {
      "dpd_mesoparticle",
      "DPD: a coarse-grained particle (mass, crystal) and its conservative potential",
      {
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
          PairStyleRegistry::schema().referable(),
          Param::file("potential_file",
                      "A YAML file holding the `potential` map (what the MD->DPD fit writes); "
                      "give this or `potential`")
              .holding("potential"),
      }};
}

MesoparticleMaterial MesoparticleMaterial::from_yaml(const YAML::Node& material) {
  return {material["mass"].as<double>(), material["lattice_constant"].as<double>(),
          material["potential"], material["atoms_per_particle"].as<double>(8.0)};
}

DpdStageParams DpdStageParams::from_yaml(const YAML::Node& p) {
  DpdStageParams s;
  s.material = p["material"].as<std::string>();
  s.box = box_from_yaml(p["box"]);
  if (p["initial"]) s.initial = initial_from_yaml(p["initial"]);
  for (const auto& b : p["bodies"]) {
    s.bodies.push_back({b["name"].as<std::string>(), geometry::region_from_yaml(b["region"]),
                        vec3(b["lattice_origin"])});
  }
  for (const auto& g : p["groups"]) {
    s.groups.push_back({g["name"].as<std::string>(), geometry::region_from_yaml(g["region"])});
  }
  for (const auto& m : p["motion"]) s.motion.push_back(motion_from_yaml(m));
  s.temperature = p["temperature"].as<double>();
  s.scheme = p["scheme"].as<std::string>();
  s.gamma = p["gamma"].as<double>();
  s.dpd_cutoff = p["dpd_cutoff"].as<double>();
  s.noise = p["noise"].as<std::string>();
  if (p["bath_temperature"]) s.bath_temperature = p["bath_temperature"].as<double>();
  s.heat_capacity = p["heat_capacity"].as<double>();
  if (const YAML::Node g = p["grid"])
    // A concurrent stage's shared grid has no `move`: its particles move
    // from the step's start (DpdGridSettings), whatever this says.
    s.grid = Grid{g["cell_size"].as<double>(), g["flip"].as<double>(),
                  !g["move"] || g["move"].as<std::string>() == "midpoint"};
  s.time_step = p["time_step"].as<double>();
  s.steps = p["steps"].as<std::int64_t>();
  s.skin = p["skin"].as<double>();
  s.sample_every = p["sample_every"].as<std::int64_t>();
  for (const auto& q : p["probes"]) s.probes.push_back(probe_from_yaml(q));
  s.particles_every = p["particles_every"].as<std::int64_t>();
  s.write_forces = p["write_forces"].as<bool>();
  s.write_internal_energy = p["write_internal_energy"].as<bool>();
  return s;
}

}  // namespace pbms::dpd
