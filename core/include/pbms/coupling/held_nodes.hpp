// Rigid groups across programs: each side of a concurrent step holds the
// nodes its own rigid groups touch, and must hold those the other side's
// groups touch as well, or its material there moves freely while the
// other side's is held (a DPD flyer striking MPM points). The sides write
// their holds as records of kHeldLanes doubles per node (coupling_side.hpp),
// the link sums them, and each keeps what the other side holds.
#pragma once

#include <span>

namespace pbms::coupling {

// `summed` (both sides' records added) becomes the other side's holds on
// the axes `own` (this side's records) leaves free: a node both hold on an
// axis keeps this side's hold there. Exact: the axes are small integers
// and the velocity on an axis one side leaves free is the other's alone.
// Throws pbms::Error when the spans' sizes differ.
void keep_other_sides_holds(std::span<double> summed, std::span<const double> own);

}  // namespace pbms::coupling
