// Whether the drivers that said Hello can run the workflow's stages. A pure
// function so the refusal logic is unit-tested without MPI.
#pragma once

#include <string>
#include <vector>

#include "pbms/config/workflow.hpp"
#include "pbms/protocol/messages.hpp"

namespace pbms::coupler {

// One line per problem; empty when every stage has a driver that declares
// its kind. `sizes[i]` is the number of processes of the app that sent
// `hellos[i]`.
std::vector<std::string> check_capabilities(const std::vector<config::StageConfig>& stages,
                                            const std::vector<protocol::Hello>& hellos,
                                            const std::vector<int>& sizes);

}  // namespace pbms::coupler
