#include "pbms/config/crystal_sampling.hpp"

namespace pbms::config {

std::vector<Param> CrystalSampling::params(int default_sampling_steps) {
  using units::Dimension;
  return {
      Param::integer("cells",
                     "Crystal size in lattice constants per edge; 0: the fewest the "
                     "cutoff allows")
          .def(0)
          .at_least(0),
      Param::real("gamma", Dimension::kNone,
                  "Sampling friction, g/mol/ps (canonical averages do not depend on it)")
          .def(1.0e4)
          .above(0),
      Param::real("time_step", Dimension::kTime, "Time step of the sampling runs")
          .def(0.01)
          .above(0),
      Param::integer("equilibration_steps", "Steps before sampling, per state")
          .def(200)
          .at_least(0),
      Param::integer("sampling_steps", "Steps sampled, per state")
          .def(default_sampling_steps)
          .at_least(10),
  };
}

CrystalSampling CrystalSampling::from_yaml(const YAML::Node& map) {
  CrystalSampling s;
  s.cells = map["cells"].as<int>();
  s.gamma = map["gamma"].as<double>();
  s.time_step = map["time_step"].as<double>();
  s.equilibration_steps = map["equilibration_steps"].as<int>();
  s.sampling_steps = map["sampling_steps"].as<int>();
  return s;
}

void CrystalSampling::write(YAML::Node& request) const {
  request["cells"] = cells;
  request["gamma"] = gamma;
  request["time_step"] = time_step;
  request["equilibration_steps"] = equilibration_steps;
  request["sampling_steps"] = sampling_steps;
}

}  // namespace pbms::config
