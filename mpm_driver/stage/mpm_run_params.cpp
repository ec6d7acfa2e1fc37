#include "mpm_run_params.hpp"

#include <cmath>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::mpm {

MpmRunParams MpmRunParams::from_yaml(const YAML::Node& p) {
  MpmRunParams r;
  r.model = MpmModelParams::from_yaml(p);
  r.metal_units = p["units"].as<std::string>() == "metal";
  if (p["time_step"].as<std::string>() != "auto") r.time_step = p["time_step"].as<double>();
  r.courant = p["courant"].as<double>();
  r.duration = p["duration"].as<double>();
  r.sample_every = p["sample_every"].as<std::int64_t>();
  r.particles_every = p["particles_every"].as<std::int64_t>();
  r.grid_every = p["grid_every"].as<std::int64_t>();
  r.gradient = p["gradient"].as<std::string>();
  if (p["period_of"]) r.period_of = p["period_of"].as<std::string>();
  r.probes = ProbeSpec::list_from_yaml(p["probes"]);
  if (p["wave_front"]) r.wave_front = WaveFrontParams::from_yaml(p["wave_front"]);
  if (p["tension"]) r.tension = RodTensionParams::from_yaml(p["tension"]);
  return r;
}

double MpmRunParams::time_step_for(double cfl_bound, double cell_size,
                                   const std::string& stage) const {
  if (!time_step) return courant * cfl_bound;
  if (*time_step > cfl_bound) {
    const char* unit = metal_units ? " ps" : "";
    throw Error(fmt::format(
        "stage '{}': time_step {:.6g}{} exceeds the CFL bound h / max(c + |v|) = {:.6g}{} "
        "(h = {:g}); use a smaller time_step or `time_step: auto`",
        stage, *time_step, unit, cfl_bound, unit, cell_size));
  }
  return *time_step;
}

std::int64_t MpmRunParams::steps(double dt) const {
  return static_cast<std::int64_t>(std::ceil(duration / dt - 1e-9));
}

}  // namespace pbms::mpm
