#include "pbms/geometry/region_yaml.hpp"

#include <vector>

#include "pbms/geometry/region_spec.hpp"

namespace pbms::geometry {

using config::Param;
using units::Dimension;

config::Param region_param(const std::string& name, const std::string& doc) {
  const std::vector<Param> block = {
      Param::real_list("lo", Dimension::kLength, "Lower corner").require().length(3, 3),
      Param::real_list("hi", Dimension::kLength, "Upper corner").require().length(3, 3)};
  const std::vector<Param> sphere = {
      Param::real_list("centre", Dimension::kLength, "Centre").require().length(3, 3),
      Param::real("radius", Dimension::kLength, "Radius").require().above(0)};
  const std::vector<Param> cylinder = {
      Param::choice("axis", {"x", "y", "z"}, "Axis direction").require(),
      Param::real_list("centre", Dimension::kLength,
                       "Centre in the two other axes, in increasing axis order")
          .require()
          .length(2, 2),
      Param::real("radius", Dimension::kLength, "Radius").require().above(0),
      Param::real("lo", Dimension::kLength, "Lower end along the axis").require(),
      Param::real("hi", Dimension::kLength, "Upper end along the axis").require()};
  Param primitive = Param::map(
      name, {Param::choice("style", {"block", "sphere", "cylinder"}, "Shape").require()}, doc);
  primitive.bounds("lo", "hi");
  primitive.discriminated_by("style")
      .variant("block", block, "Axis-aligned box")
      .variant("sphere", sphere, "Ball")
      .variant("cylinder", cylinder, "Axis-aligned circular cylinder");
  Param r = Param::map(
      name,
      {Param::choice(
           "style", {"block", "sphere", "cylinder", "union", "intersection", "difference"}, "Shape")
           .require()},
      doc);
  r.bounds("lo", "hi");
  const std::vector<Param> composite = {
      Param::list_of("of", primitive, "The regions combined (difference: first minus the others)")
          .require()
          .length(2, 16)};
  r.discriminated_by("style")
      .variant("block", block, "Axis-aligned box")
      .variant("sphere", sphere, "Ball")
      .variant("cylinder", cylinder, "Axis-aligned circular cylinder")
      .variant("union", composite, "Points in any of the regions")
      .variant("intersection", composite, "Points in all of the regions")
      .variant("difference", composite, "Points in the first region and none of the others");
  return r;
}

namespace {

RegionSpec region_spec(const YAML::Node& n) {
  RegionSpec spec;
  spec.style = n["style"].as<std::string>();
  for (const auto& kv : n) {
    const auto key = kv.first.as<std::string>();
    if (key == "style") continue;
    if (key == "of") {
      for (const auto& child : kv.second) spec.children.push_back(region_spec(child));
    } else if (key == "axis") {
      spec.words[key] = kv.second.as<std::string>();
    } else if (kv.second.IsSequence()) {
      spec.params[key] = kv.second.as<std::vector<double>>();
    } else {
      spec.params[key] = {kv.second.as<double>()};
    }
  }
  return spec;
}

}  // namespace

std::unique_ptr<Region> region_from_yaml(const YAML::Node& node) {
  return RegionRegistry::create(region_spec(node));
}

}  // namespace pbms::geometry
