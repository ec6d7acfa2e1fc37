// Everything a particle pass reads or writes at one grid node, packed in
// eight doubles: one cache line, one AVX-512 register (two AVX2, four SSE2).
// A point's contribution to a node is then a few whole-record multiply-adds
// instead of a scalar update per field, and a node costs one cache line
// however many fields a pass touches.
#pragma once

#include "pbms/simd/lanes8.hpp"

namespace pbms::grid {

// Wrapped so that std::vector keeps the alignment (a vector of the bare
// attribute type would drop it, with a warning).
struct alignas(64) NodeLanes {
  Lanes8 lanes;
};

// The particle-to-grid sums of a node: mass, momentum, force.
namespace sums {
inline constexpr int kMass = 0;
inline constexpr int kMomentum = 1;  // 1, 2, 3
inline constexpr int kVector = 3;    // lanes of the momentum or the force
inline constexpr int kForce = 4;     // 4, 5, 6
inline constexpr int kHeldAxes = 7;  // MpmSolver::mark_held_nodes
inline constexpr int kStride = 8;    // doubles from one node's sums to the next
}  // namespace sums

}  // namespace pbms::grid
