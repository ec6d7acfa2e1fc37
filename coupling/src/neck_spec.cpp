#include "pbms/coupling/neck_spec.hpp"

#include "pbms/config/axis_name.hpp"

namespace pbms::coupling {

using config::OutputSpec;
using config::Param;
using units::Dimension;

Param necks_param() {
  return Param::list_of(
             "necks",
             Param::map(
                 "neck",
                 {Param::identifier("name", "Key suffix: neck_<name>, neck_width_<name>, ...")
                      .require(),
                  Param::identifier("first", "One body (a group)")
                      .require()
                      .names_entry_of({"bodies", "groups"}),
                  Param::identifier("second", "The other body")
                      .require()
                      .names_entry_of({"bodies", "groups"}),
                  Param::choice("second_rod_axis", {"x", "y", "z"},
                                "The second body is a rod along this axis: the line runs "
                                "from the first body's centre square onto the rod's axis")},
                 "A neck between two bodies"),
             "Necks between sintering bodies (seed §6.4): the smallest diameter of their "
             "cross-section perpendicular to the line through their centres of mass, in slabs "
             "a plane spacing (a/2) thick over the middle half of that line, each slab's "
             "diameter that of the circle of its particles' area (a³/4 each over the slab's "
             "thickness), counting the particles within half the centre distance of the line; "
             "0 before they touch")
      .def(std::vector<std::string>{});
}

Param neck_stable_time_param() {
  return Param::real("neck_stable_time", Dimension::kTime,
                     "neck_width_<name> is the mean over the run's last this much")
      .def(20.0)
      .above(0);
}

std::vector<OutputSpec> neck_outputs() {
  return {
      {"neck_<name>", OutputSpec::Shape::kTable, "",
       "Each sample: the neck's width, the distance between the two bodies' centres and the "
       "closest approach of their particles (capped at 2 a)"},
      {"neck_width_<name>", OutputSpec::Shape::kScalar, "Å",
       "The stable neck: the mean width over the last neck_stable_time"},
      {"neck_final_<name>", OutputSpec::Shape::kScalar, "Å", "The neck's width at the end"},
      {"contact_time_<name>", OutputSpec::Shape::kScalar, "ps",
       "First sample where a particle of each body is within 1.1 nearest-neighbour distances "
       "(1.1 a/√2) of the other (absent if never)"},
  };
}

std::vector<NeckPair> necks_from_yaml(const YAML::Node& necks) {
  std::vector<NeckPair> out;
  for (const auto& n : necks) {
    const YAML::Node axis = n["second_rod_axis"];
    out.push_back({n["name"].as<std::string>(), n["first"].as<std::string>(),
                   n["second"].as<std::string>(),
                   axis ? config::axis_index(axis.as<std::string>()) : -1});
  }
  return out;
}

}  // namespace pbms::coupling
