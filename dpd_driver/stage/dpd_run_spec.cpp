#include "dpd_run.hpp"
#include "dpd_stage_params.hpp"
#include "pbms/analysis/tension_test.hpp"
#include "pbms/coupling/neck_spec.hpp"

namespace pbms::dpd {

using config::OutputSpec;
using config::Param;
using units::Dimension;

namespace {

std::vector<OutputSpec> common_outputs() {
  std::vector<OutputSpec> out{
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
  for (auto& o : coupling::neck_outputs()) out.push_back(std::move(o));
  return out;
}

}  // namespace

config::StageKindSpec DpdRunStage::spec() {
  config::StageKindSpec s;
  s.kind = "dpd_run";
  s.checkpoints = true;
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
  s.params.push_back(
      Param::map(
          "impact",
          {Param::identifier("near_slab", "Group nearer the impact face")
               .require()
               .names_entry_of({"bodies", "groups"}),
           Param::identifier("far_slab", "Group farther from the impact face")
               .require()
               .names_entry_of({"bodies", "groups"}),
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
               .above(0),
           Param::table("baseline",
                        "The `slabs` table of an earlier dpd_run impact stage of the same body "
                        "and start without the impact, whose noise this stage takes "
                        "(`noise_of`): its histories are subtracted from this stage's before any "
                        "arrival is timed, which removes the body's own drift and most of its "
                        "thermal motion (the subtraction technique of nonequilibrium MD)"),
           Param::real_list("pulse_levels", Dimension::kLength,
                            "pulse_speed: the lowest and highest of 8 displacement levels, "
                            "equally spaced in their logarithm, at which the slabs' delays are "
                            "averaged")
               .length(2, 2)
               .def(std::vector<double>{0.05, 0.4})},
          "mode: impact")
          .required_when("mode", "impact"));
  std::vector<Param> tension = {
      Param::identifier("specimen", "The rod: a body or group, grips included")
          .require()
          .names_entry_of({"bodies", "groups"}),
      Param::choice("axis", {"x", "y", "z"}, "Pulling direction").def(std::string("x")),
      Param::real("area", Dimension::kNone,
                  "Cross-section, Å^2 (default: the nominal one, the specimen's sites times "
                  "a^3/4 over its length; its lateral extents at 298 K are wider by the "
                  "outermost sites' thermal excursions)")
          .above(0),
      Param::map("grips",
                 {Param::identifier("left", "The grip group at the low end")
                      .require()
                      .names_entry_of({"bodies", "groups"}),
                  Param::identifier("right", "The grip group at the high end")
                      .require()
                      .names_entry_of({"bodies", "groups"})},
                 "The grip groups, whose pull over the cross-section gives "
                 "grip_youngs_modulus")};
  for (auto& q : analysis::TensionTest::params()) tension.push_back(std::move(q));
  s.params.push_back(
      Param::map("tension", std::move(tension),
                 "mode: tension. Stress is the specimen's mean conservative virial stress, strain "
                 "its elongation over its length")
          .required_when("mode", "tension"));
  s.params.push_back(coupling::necks_param());
  s.params.push_back(coupling::neck_stable_time_param());
  s.params.push_back(
      Param::identifier("noise_of",
                        "Draw the pair noise and any velocities as this earlier dpd_run stage "
                        "did (the run seed mixed with its name, not this stage's), so that a "
                        "stage and its impact.baseline share their thermal noise")
          .earlier_stage({"dpd_run"}));
  s.outputs = common_outputs();
  s.outputs.push_back({"slabs", OutputSpec::Shape::kTable, "",
                       "time, near_displacement, far_displacement of the two slabs every step "
                       "and, with a baseline, near_response and far_response: the same less the "
                       "baseline's (impact)"});
  s.outputs.push_back({"pulse_speed", OutputSpec::Shape::kScalar, "m/s",
                       "Distance between the slabs over the mean delay of their displacements "
                       "(responses, with a baseline) at impact.pulse_levels (impact)"});
  s.outputs.push_back({"pulse", OutputSpec::Shape::kTable, "",
                       "level, delay, speed: the slabs' delay and the speed it gives at each "
                       "of pulse_speed's levels (impact)"});
  s.outputs.push_back({"baseline_residual", OutputSpec::Shape::kScalar, "Å",
                       "The largest far-slab response before the near slab's first motion: how "
                       "well the baseline cancels the body's own motion (impact, with a "
                       "baseline)"});
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
  s.checkpoints = true;
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
  s.params.push_back(coupling::necks_param());
  s.params.push_back(coupling::neck_stable_time_param());
  s.outputs = common_outputs();
  return s;
}

}  // namespace pbms::dpd
