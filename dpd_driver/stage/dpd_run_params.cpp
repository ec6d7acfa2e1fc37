#include "dpd_run_params.hpp"

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::dpd {

SlabBaseline SlabBaseline::from_yaml(const YAML::Node& table) {
  const auto column = [&](const char* name) {
    if (!table[name]) {
      throw Error(
          fmt::format("impact.baseline: the table has no column '{}': it must be the "
                      "`slabs` table of an earlier dpd_run impact stage",
                      name));
    }
    return table[name]["values"].as<std::vector<double>>();
  };
  SlabBaseline b{column("time"), column("near_displacement"), column("far_displacement")};
  return b;
}

ImpactParams ImpactParams::from_yaml(const YAML::Node& impact) {
  ImpactParams i;
  i.near_slab = impact["near_slab"].as<std::string>();
  i.far_slab = impact["far_slab"].as<std::string>();
  i.axis = axis_index(impact["axis"].as<std::string>());
  i.threshold = impact["threshold"].as<double>();
  i.mid_amplitude = impact["arrival"].as<std::string>() == "mid_amplitude";
  i.smoothing = impact["smoothing"].as<double>();
  i.window = impact["window"].as<double>();
  if (const YAML::Node b = impact["baseline"]) i.baseline = SlabBaseline::from_yaml(b);
  const auto levels = impact["pulse_levels"].as<std::vector<double>>();
  i.pulse_lo = levels.at(0);
  i.pulse_hi = levels.at(1);
  return i;
}

TensionParams TensionParams::from_yaml(const YAML::Node& tension) {
  TensionParams t;
  t.specimen = tension["specimen"].as<std::string>();
  t.axis = axis_index(tension["axis"].as<std::string>());
  if (tension["area"]) t.area = tension["area"].as<double>();
  if (const YAML::Node g = tension["grips"]) {
    t.grips = std::make_pair(g["left"].as<std::string>(), g["right"].as<std::string>());
  }
  t.test = analysis::TensionTest::from_yaml(tension);
  return t;
}

DpdRunParams DpdRunParams::from_yaml(const YAML::Node& p) {
  DpdRunParams r;
  const auto mode = p["mode"].as<std::string>();
  r.mode = mode == "impact" ? Mode::kImpact : mode == "tension" ? Mode::kTension : Mode::kFree;
  r.stage = DpdStageParams::from_yaml(p);
  if (r.mode == Mode::kImpact && p["impact"]) r.impact = ImpactParams::from_yaml(p["impact"]);
  if (r.mode == Mode::kTension && p["tension"]) r.tension = TensionParams::from_yaml(p["tension"]);
  r.necks = coupling::necks_from_yaml(p["necks"]);
  r.neck_stable_time = p["neck_stable_time"].as<double>();
  if (p["noise_of"]) r.noise_of = p["noise_of"].as<std::string>();
  return r;
}

DpdRunParams DpdRunParams::equilibrate_from_yaml(const YAML::Node& p) {
  DpdRunParams r;
  r.mode = Mode::kEquilibrate;
  r.stage = DpdStageParams::from_yaml(p);
  r.target_temperature = p["target_temperature"].as<double>();
  r.tau = p["tau"].as<double>();
  r.necks = coupling::necks_from_yaml(p["necks"]);
  r.neck_stable_time = p["neck_stable_time"].as<double>();
  return r;
}

}  // namespace pbms::dpd
