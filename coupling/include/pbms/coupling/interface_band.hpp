// The interface band of a concurrent run: the grid nodes where particles
// of both programs may deposit mass, momentum and force, and so the only
// nodes the nodal sums across programs need to carry.
//
// Built from the two regions' bounding boxes, each grown by `margin` (how
// far a particle may travel from its region during the run, plus the
// reach of its shape functions), so it is exact for the planar interfaces
// of the seed's cases and a safe superset for curved ones. A coupling
// scheme checks every step that no particle deposits outside its own
// region's band side (InterfaceBand::covers) and stops the run, naming the
// particle, rather than sum an incomplete node.
#pragma once

#include "pbms/geometry/region.hpp"
#include "pbms/grid/regular_grid.hpp"

namespace pbms::coupling {

class InterfaceBand {
 public:
  // Throws pbms::Error when the grown boxes do not meet (the regions are
  // too far apart to exchange anything) or the band misses the grid.
  InterfaceBand(const grid::RegularGrid& grid, const geometry::Region& a, const geometry::Region& b,
                double margin);

  // The band as a box of global node indices.
  [[nodiscard]] const grid::NodeBox& nodes() const { return nodes_; }
  // The band in space: the closed box the two grown bounding boxes share.
  [[nodiscard]] const geometry::Box& box() const { return box_; }
  // Whether a particle at x deposits only onto nodes in the band, or onto
  // none of them (its whole stencil is outside).
  [[nodiscard]] bool covers(const geometry::Vec3& x) const;

 private:
  grid::RegularGrid grid_;
  geometry::Box box_;
  grid::NodeBox nodes_;
};

}  // namespace pbms::coupling
