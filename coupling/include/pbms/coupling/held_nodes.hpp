// Rigid groups across programs: each side of a concurrent step holds the
// nodes its own rigid groups touch, and must hold those the other side's
// groups touch as well, or its material there moves freely while the
// other side's is held (a DPD flyer striking MPM points). The sides write
// their holds as records of kHeldLanes doubles per node (coupling_side.hpp),
// the link sums them, and each keeps what the other side holds.
#pragma once

#include <span>
#include <vector>

#include "pbms/coupling/coupling_side.hpp"

namespace pbms::coupling {

// `summed` (both sides' records added) becomes the other side's holds on
// the axes `own` (this side's records) leaves free: a node both hold on an
// axis keeps this side's hold there. Exact: the axes are small integers
// and the velocity on an axis one side leaves free is the other's alone.
// Throws pbms::Error when the spans' sizes differ.
void keep_other_sides_holds(std::span<double> summed, std::span<const double> own);

// One side's part in a step's swap of held nodes.
class HeldNodeSwap {
 public:
  // A new step: nothing swapped yet.
  void reset() { summed_.clear(); }
  // When the link asks: this side's holds on `nodes`, written by `write`
  // (kHeldLanes doubles a node), kept, and handed over for the link to sum.
  template <class Write>
  [[nodiscard]] NodalRecords offer(const grid::NodeBox& nodes, Write&& write) {
    summed_.assign(static_cast<std::size_t>(nodes.count()) * kHeldLanes, 0.0);
    write(summed_.data());
    own_ = summed_;
    return {summed_.data(), kHeldLanes, nodes};
  }
  // After the sum: the other side's holds (keep_other_sides_holds), or
  // null when nothing was swapped this step.
  [[nodiscard]] const double* others() {
    if (summed_.empty()) return nullptr;
    keep_other_sides_holds(summed_, own_);
    return summed_.data();
  }

 private:
  std::vector<double> summed_, own_;
};

}  // namespace pbms::coupling
