// Frictionless contact between two velocity fields that share grid nodes
// (the multi-material MPM of Bardenhagen, Brackbill & Sulsky, 2000): a gas
// around a body keeps its own nodal velocity, slides freely along the
// body's surface, and cannot pass through it. At a node both fields reach,
// the body and the gas take a common normal velocity when they approach
// along the surface normal, and each keeps its own otherwise. Physics
// only: what one node's two records give, no grid, no MPI.
#pragma once

#include <array>

namespace pbms::grid {

using ContactVec = std::array<double, 3>;

// The unit normal from field a's material into field b's at a node, from
// the two fields' nodal mass gradients: b's mass rises and a's falls that
// way. Zero where the two gradients cancel (no surface there).
// contact_normal(b's gradient, a's gradient) is its negative bit for bit.
ContactVec contact_normal(const ContactVec& grad_a, const ContactVec& grad_b);

// The momentum field a gains at a node from its contact with field b
// (masses ma, mb > 0; momenta pa, pb after the step's forces; n from
// contact_normal(grad_a, grad_b)): if a approaches b along n, the reduced
// mass times that approach, against n, so that both then move alike along
// n and their tangential motion is left alone; else nothing. Called with
// the two fields swapped (and n negated), it returns the exact negative:
// the two programs that hold the fields conserve momentum bit for bit.
ContactVec frictionless_contact_impulse(double ma, const ContactVec& pa, double mb,
                                        const ContactVec& pb, const ContactVec& n);

}  // namespace pbms::grid
