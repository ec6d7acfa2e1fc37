// Where the gas around a concurrent stage's body starts: the sites of a
// simple cubic lattice over the box that no particle of the body is near
// (seed §6.2: the inclusion's 21³ lattice less the cube's 11³ sites), and
// which of them are far enough from the body to measure the gas's own
// pressure. Pure geometry, the same on every rank.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/geometry/region.hpp"

namespace pbms::coupling {

// For each of `points`, whether some position of `body` lies within
// `distance` of it (no periodic images).
[[nodiscard]] std::vector<bool> near_body(const std::vector<geometry::Vec3>& points,
                                          const std::vector<geometry::Vec3>& body, double distance);

// An fcc crystal's holes have 4 (tetrahedral, at 0.433 a) or 6
// (octahedral, at 0.5 a) sites around them within 0.6 a, with room for a
// relaxed surface's holes (their fourth neighbour measured at 0.555 a in a
// ball of 141 particles at 298 K); a point outside a surface has at most 3
// there (a (111) hollow), or 4 only when it sits within 0.33 a of a (100)
// face's plane, inside the surface's own half plane spacing.
inline constexpr double kInterstitialReach = 0.6;  // lattice constants
inline constexpr std::size_t kInterstitialNeighbours = 4;

// For each of `points`, whether it lies in a hole of the body's fcc crystal
// of `lattice_constant`: kInterstitialNeighbours or more body positions
// within kInterstitialReach lattice constants. A gas lattice finer than
// the crystal has sites there that no clearance small enough to let the gas
// reach the surface removes.
[[nodiscard]] std::vector<bool> in_interstices(const std::vector<geometry::Vec3>& points,
                                               const std::vector<geometry::Vec3>& body,
                                               double lattice_constant);

// The lattice sites of `gas` within `box` (its faces included on the axes
// not `periodic`, the upper face left out on periodic ones, where it is the
// lower face's image) farther than gas.clearance from every body position
// and not in the holes of the body's crystal (in_interstices; a
// `lattice_constant` of 0 skips that).
[[nodiscard]] std::vector<geometry::Vec3> gas_sites(const GasParams& gas, const geometry::Box& box,
                                                    const std::array<bool, 3>& periodic,
                                                    const std::vector<geometry::Vec3>& body,
                                                    double lattice_constant);

}  // namespace pbms::coupling
