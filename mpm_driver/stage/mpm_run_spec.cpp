#include "mpm_run.hpp"
#include "pbms/analysis/tension_test.hpp"
#include "pbms/geometry/region_yaml.hpp"
#include "pbms/grid/shape_function.hpp"

namespace pbms::mpm {

using config::OutputSpec;
using config::Param;
using units::Dimension;

using geometry::region_param;

namespace {

Param axes_param(const std::string& doc) {
  return Param::list_of("axes", Param::choice("axis", {"x", "y", "z"}, "An axis"), doc)
      .length(1, 3);
}

}  // namespace

config::StageKindSpec MpmRunStage::spec() {
  config::StageKindSpec s;
  s.kind = "mpm_run";
  s.checkpoints = true;
  s.program = "mpm_driver";
  s.doc =
      "Explicit material point method run (update-stress-last or -first, FLIP/PIC, plain or "
      "DDMP gradients) of bodies filled with points on a background grid";
  s.material_kinds = {"linear_elastic", "j2_plasticity", "cubic_j2_plasticity", "ideal_gas"};

  const Param grid = Param::map(
      "grid",
      {
          Param::real_list("origin", Dimension::kLength, "Lower corner of the grid")
              .def(std::vector<double>{0.0, 0.0, 0.0})
              .length(3, 3),
          Param::real("cell_size", Dimension::kLength, "Edge h of the cubic cells")
              .require()
              .above(0),
          Param::int_list("cells", "Cells along x, y, z").require().length(3, 3).at_least(1),
          Param::list_of("periodic", Param::choice("axis", {"x", "y", "z"}, "An axis"),
                         "Periodic axes; the others are closed by the grid's faces")
              .def(std::vector<std::string>{})
              .length(0, 3),
      },
      "The background grid");

  const Param axial_mode = Param::map(
      "axial_mode",
      {
          Param::choice("axis", {"x", "y", "z"}, "Axis of the bar").require(),
          Param::real("amplitude", Dimension::kVelocity, "Velocity amplitude v0").require(),
          Param::real("fixed_end", Dimension::kLength, "Coordinate of the fixed end").require(),
          Param::real("length", Dimension::kLength, "Length L of the bar").require().above(0),
      },
      "Adds the first axial mode of a fixed-free bar, v0 sin(pi s / 2L), s from the fixed end");
  const Param body = Param::map(
      "body",
      {
          Param::identifier("name", "Body name; also a group of its points").require(),
          Param::identifier("material", "Material of the body").require().material(),
          region_param("region", "Region the body fills").require(),
          Param::int_list("points_per_cell",
                          "Material points per cell and axis: one number or x, y, z")
              .def(std::vector<int>{2})
              .length(1, 3)
              .length_one_of({1, 3})
              .at_least(1),
          Param::real_list("velocity", Dimension::kVelocity, "Initial velocity")
              .def(std::vector<double>{0.0, 0.0, 0.0})
              .length(3, 3),
          Param::real("pressure", Dimension::kPressure, "Initial hydrostatic pressure").def(0.0),
          axial_mode,
      },
      "A body of one material");
  const Param group = Param::map(
      "group",
      {Param::identifier("name", "Group name").require(),
       region_param("region", "The group holds the points inside this region at the start")
           .require()},
      "A named set of points");

  Param bc = Param::map(
      "condition",
      {Param::choice("kind", {"nodes", "group_velocity", "group_force"}, "What is prescribed")
           .require()},
      "One boundary condition");
  bc.discriminated_by("kind")
      .variant("nodes",
               {region_param("region",
                             "Grid nodes inside this region (block regions select a box of nodes)")
                    .require(),
                axes_param("Velocity components prescribed").require(),
                Param::real_list("velocity", Dimension::kVelocity, "Prescribed velocity; 0 fixes")
                    .def(std::vector<double>{0.0, 0.0, 0.0})
                    .length(3, 3)},
               "Prescribed (default zero) velocity components on grid nodes")
      .variant("group_velocity",
               {Param::identifier("group", "Group of points")
                    .require()
                    .names_entry_of({"bodies", "groups"}),
                axes_param("Velocity components prescribed").require(),
                Param::real_list("velocity", Dimension::kVelocity, "Prescribed velocity")
                    .require()
                    .length(3, 3),
                Param::real("ramp_time", Dimension::kTime,
                            "Reach the velocity linearly over this time from rest (0: at once), "
                            "as a DPD rigid group's ramp_time")
                    .def(0.0)
                    .at_least(0)},
               "Points of a group moved at a prescribed velocity (grips, flyers, pistons), "
               "with the nodes they touch. A slow compression to large strain needs "
               "gradient: ddmp with ddmp_blend: face_vanishing (docs/mpm-driver.md, Known "
               "limits)")
      .variant("group_force",
               {Param::identifier("group", "Group of points")
                    .require()
                    .names_entry_of({"bodies", "groups"}),
                Param::real_list("force", Dimension::kForce,
                                 "Total force, shared evenly by the group's points (a traction "
                                 "times the face area)")
                    .require()
                    .length(3, 3)},
               "A constant external force on a group");

  Param probe =
      Param::map("probe",
                 {Param::identifier("name", "Column prefix in the probes table").require(),
                  Param::choice("kind",
                                {"energy", "momentum", "mean_stress", "slab_displacement",
                                 "group_force", "group_extent", "group_volume"},
                                "What is sampled")
                      .require()},
                 "A quantity sampled every sample_every steps");
  probe.discriminated_by("kind")
      .variant("energy", {}, "Kinetic, stored (strain or internal), dissipated and total energy")
      .variant("momentum", {}, "Total momentum")
      .variant("mean_stress",
               {Param::identifier("group", "Group of points")
                    .require()
                    .names_entry_of({"bodies", "groups"})},
               "Volume-weighted mean stress (xx yy zz yz xz xy) and pressure of a group")
      .variant("slab_displacement",
               {Param::identifier("group", "Group of points")
                    .require()
                    .names_entry_of({"bodies", "groups"})},
               "Centre-of-mass displacement of a group from its start")
      .variant("group_force",
               {Param::identifier("group", "Group of points")
                    .require()
                    .names_entry_of({"bodies", "groups"})},
               "Force the group's prescribed velocity exerts on it (the grip reaction)")
      .variant("group_extent",
               {Param::identifier("group", "Group of points")
                    .require()
                    .names_entry_of({"bodies", "groups"}),
                Param::choice("axis", {"x", "y", "z"}, "Axis").require()},
               "Largest minus smallest coordinate of the group's points")
      .variant("group_volume",
               {Param::identifier("group", "Group of points")
                    .require()
                    .names_entry_of({"bodies", "groups"})},
               "Sum of the current volumes of the group's points");

  const Param wave_front = Param::map(
      "wave_front",
      {
          Param::identifier("group", "The bar: a group or body")
              .require()
              .names_entry_of({"bodies", "groups"}),
          Param::real("loaded_end", Dimension::kLength, "x of the loaded end").require(),
          Param::real("fixed_end", Dimension::kLength, "x of the fixed end").require(),
          Param::real("traction", Dimension::kPressure, "Applied end stress f/A").require(),
          Param::real("profile_time", Dimension::kTime,
                      "Time of the stress profile compared with the exact solution")
              .require()
              .above(0),
          Param::real("rms_reference", Dimension::kPressure,
                      "RMS of another run's profile (plain MPM); gives rms_ratio_mpm_over_ddmp")
              .referable(),
          Param::real("variation_reference", Dimension::kPressure,
                      "Excess variation of another run's profile (plain MPM); gives "
                      "variation_ratio_mpm_over_ddmp")
              .referable(),
      },
      "1-D bar analysis: wave-front speed, plateau stress and the profile against the exact "
      "solution with reflections");

  std::vector<Param> tension_keys = {
      Param::identifier("specimen", "The rod: a group or body, grips included")
          .require()
          .names_entry_of({"bodies", "groups"}),
      Param::choice("axis", {"x", "y", "z"}, "Pulling direction").def(std::string("x"))};
  for (auto& q : analysis::TensionTest::params()) tension_keys.push_back(std::move(q));
  const Param tension = Param::map(
      "tension", std::move(tension_keys),
      "Tension test of a rod (metal units): stress is the integral of the axial stress over "
      "the rod's points divided by its starting cross-section times its current length, "
      "strain its elongation over its length (each extent plus one point spacing), as "
      "dpd_run's tension measures a DPD rod");

  s.params = {
      Param::choice("units", {"metal", "consistent"},
                    "metal: LAMMPS metal units; consistent: plain numbers of one consistent "
                    "system (the seed's non-dimensional bar)")
          .def(std::string("metal")),
      grid,
      Param::choice("shape_function", grid::ShapeFunctionRegistry::names(), "Shape function style")
          .def(std::string("linear")),
      Param::choice("gradient", {"plain", "ddmp"},
                    "plain: gradients of the shape functions; ddmp: dual-domain (Zhang, Ma & "
                    "Giguere 2011), on any number of ranks")
          .def(std::string("plain")),
      Param::choice("ddmp_blend", {"none", "face_vanishing"},
                    "With ddmp: pure dual-domain gradients, or blended with the plain ones by "
                    "4 xi (1 - xi) per axis as in the seed")
          .def(std::string("none")),
      Param::choice("stress_update", {"last", "first"}, "When the stress is updated")
          .def(std::string("last")),
      Param::real("flip", Dimension::kNone, "FLIP fraction of the velocity update: 1 FLIP, 0 PIC")
          .def(1.0)
          .at_least(0)
          .at_most(1),
      Param::real("small_mass_fraction", Dimension::kNone,
                  "Nodes lighter than this fraction of the lightest point are skipped")
          .def(1e-3)
          .at_least(0),
      Param::list_of("bodies", body, "The bodies").require().length(1, 16).with_stage_names(),
      Param::list_of("groups", group, "Named groups of points")
          .def(std::vector<std::string>{})
          .with_stage_names(),
      Param::list_of("boundary", bc, "Boundary conditions").def(std::vector<std::string>{}),
      Param::real_list("body_acceleration", Dimension::kAcceleration, "Uniform body acceleration")
          .def(std::vector<double>{0.0, 0.0, 0.0})
          .length(3, 3),
      Param::real("time_step", Dimension::kTime,
                  "Time step, or auto: courant * h / max(c + |v|). A value above h / max(c + "
                  "|v|) is refused")
          .def(std::string("auto"))
          .or_auto()
          .above(0),
      Param::real("courant", Dimension::kNone, "Fraction of the CFL bound used by time_step: auto")
          .def(0.5)
          .above(0)
          .at_most(1),
      Param::real("duration", Dimension::kTime, "Simulated time").require().above(0),
      Param::integer("sample_every", "Steps between probe samples").def(10).above(0),
      Param::list_of("probes", probe, "Sampled quantities").def(std::vector<std::string>{}),
      Param::integer("particles_every", "Steps between H5MD particle frames; 0 writes none")
          .def(0)
          .at_least(0),
      Param::integer("grid_every", "Steps between XDMF grid frames; 0 writes none")
          .def(0)
          .at_least(0),
      wave_front,
      tension,
      Param::string("period_of",
                    "A probe column (e.g. tip.x); its oscillation period is reported as `period`"),
  };
  s.outputs = {
      {"steps", OutputSpec::Shape::kScalar, "1", "Time steps taken"},
      {"time_step", OutputSpec::Shape::kScalar, "ps", "Time step used"},
      {"particles", OutputSpec::Shape::kScalar, "1", "Material points"},
      {"energy_drift", OutputSpec::Shape::kScalar, "1",
       "(E_end - E_0) / E_0 of the total energy (with an energy probe)"},
      {"energy_max_deviation", OutputSpec::Shape::kScalar, "1",
       "Largest |E - E_0| / E_0 over the samples (with an energy probe)"},
      {"wave_speed", OutputSpec::Shape::kScalar, "Å/ps", "Front speed (wave_front)"},
      {"plateau_stress", OutputSpec::Shape::kScalar, "bar", "Stress behind the front (wave_front)"},
      {"rms_from_exact", OutputSpec::Shape::kScalar, "bar",
       "RMS of the stress profile from the exact solution (wave_front)"},
      {"rms_ratio_mpm_over_ddmp", OutputSpec::Shape::kScalar, "1",
       "rms_reference / rms_from_exact (wave_front)"},
      {"excess_variation", OutputSpec::Shape::kScalar, "bar",
       "Total variation of the profile beyond the exact one's jumps (wave_front)"},
      {"variation_ratio_mpm_over_ddmp", OutputSpec::Shape::kScalar, "1",
       "variation_reference / excess_variation (wave_front)"},
      {"exact_wave_speed", OutputSpec::Shape::kScalar, "Å/ps",
       "sqrt(M / rho) of the bar (wave_front)"},
      {"period", OutputSpec::Shape::kScalar, "ps", "Oscillation period of period_of"},
      {"probes", OutputSpec::Shape::kTable, "", "Probe samples"},
      {"profile", OutputSpec::Shape::kTable, "", "Stress profile and exact solution (wave_front)"},
  };
  for (auto& o : analysis::TensionTest::outputs("tension")) s.outputs.push_back(std::move(o));
  return s;
}

}  // namespace pbms::mpm
