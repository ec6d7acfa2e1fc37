// What a stage's {from: stage.output} keys stand for once the earlier
// stages have run: the coupler puts the values in before it sends a stage
// to its driver, so the drivers never see a reference.
#pragma once

#include <map>
#include <string>

#include <yaml-cpp/yaml.h>

#include "pbms/error.hpp"
#include "pbms/results.hpp"

namespace pbms::coupler {

// A reference to a scalar its stage could not measure (NaN or infinite):
// the stage that takes it would run on a meaningless number.
struct NonFiniteReference : Error {
  using Error::Error;
};

// Every {from: stage.output} under `node` replaced with that output of an
// earlier stage: a scalar in metal units, a table as a map of columns, a
// map output as the map. Throws pbms::Error for an output the stage did
// not produce, NonFiniteReference (naming `path` and the key under it) for
// one it produced as NaN or infinite.
[[nodiscard]] YAML::Node resolve_references(const YAML::Node& node,
                                            const std::map<std::string, StageResults>& done,
                                            const std::string& path);

// The materials a stage can see: every one whose references are already
// resolvable (the validator made sure that a stage's own materials are).
// A material whose reference is NaN is an error all the same.
[[nodiscard]] YAML::Node resolve_materials(const YAML::Node& materials,
                                           const std::map<std::string, StageResults>& done);

}  // namespace pbms::coupler
