// Where the gas around a concurrent stage's body starts: the sites of a
// simple cubic lattice over the box that no particle of the body is near
// (seed §6.2: the inclusion's 21³ lattice less the cube's 11³ sites), and
// which of them are far enough from the body to measure the gas's own
// pressure. Pure geometry, the same on every rank.
#pragma once

#include <array>
#include <vector>

#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/geometry/region.hpp"

namespace pbms::coupling {

// For each of `points`, whether some position of `body` lies within
// `distance` of it (no periodic images).
[[nodiscard]] std::vector<bool> near_body(const std::vector<geometry::Vec3>& points,
                                          const std::vector<geometry::Vec3>& body, double distance);

// The lattice sites of `gas` within `box` (its faces included on the axes
// not `periodic`, the upper face left out on periodic ones, where it is the
// lower face's image) farther than gas.clearance from every body position.
[[nodiscard]] std::vector<geometry::Vec3> gas_sites(const GasParams& gas, const geometry::Box& box,
                                                    const std::array<bool, 3>& periodic,
                                                    const std::vector<geometry::Vec3>& body);

}  // namespace pbms::coupling
