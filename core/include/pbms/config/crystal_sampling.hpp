// How dpd_driver samples a periodic crystal at a temperature: the keys its
// properties stages take (dpd_elastic, dpd_isotherm, dpd_uniaxial_strain)
// and the MD->DPD fit's `judge` map, whose requests those stages answer.
// Declared once here, so that the two programs cannot disagree on a key or
// a default.
#pragma once

#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/param.hpp"

namespace pbms::config {

struct CrystalSampling {
  int cells = 0;  // lattice constants per edge; 0: the fewest the cutoff allows
  int equilibration_steps = 200;
  int sampling_steps = 2000;
  double gamma = 1.0e4;     // g/mol/ps
  double time_step = 0.01;  // ps

  // The keys, with `default_sampling_steps` as sampling_steps' default.
  static std::vector<Param> params(int default_sampling_steps);
  // From a checked map holding the keys (defaults filled).
  static CrystalSampling from_yaml(const YAML::Node& map);
  // The keys of a request to one of the properties stages.
  void write(YAML::Node& request) const;
};

}  // namespace pbms::config
