#include "engine/concurrent_mpm_side.hpp"

#include <limits>

namespace pbms::mpm {

ConcurrentMpmSide::ConcurrentMpmSide(MpmEngine& engine, double dt) : engine_(engine), dt_(dt) {}

void ConcurrentMpmSide::map_to_grid() {
  engine_.begin_step();
  engine_.map_to_grid(dt_);
  engine_.complete_nodal_sums();
}

coupling::NodalRecords ConcurrentMpmSide::nodal_records() {
  const auto s = engine_.solver().nodal_sums();
  return {s.data, s.stride, s.nodes};
}

void ConcurrentMpmSide::update_and_map_back() {
  engine_.update_nodes(dt_);
  engine_.map_to_points(dt_);
  engine_.complete_remap_sums();
}

// The reactions belong to this step's point order, which the migration
// changes.
void ConcurrentMpmSide::finish_step() {
  engine_.update_stress_and_move(dt_);
  engine_.boundary_conditions().point_forces = {};
  reactions_.clear();
  engine_.migrate();
}

coupling::ContinuumSide::Points ConcurrentMpmSide::partner_points() const {
  const MaterialPoints& p = engine_.points();
  return {p.id, p.x, p.v, p.mass};
}

// The space of this rank's cells, which hold its points after every
// migration; the outermost boxes own beyond the grid on free axes.
coupling::SpaceBox ConcurrentMpmSide::points_box() const {
  const grid::GridPartition& part = engine_.partition();
  const grid::CellBox cells = part.cells_of(engine_.rank());
  const grid::RegularGrid& g = part.grid();
  constexpr double inf = std::numeric_limits<double>::infinity();
  coupling::SpaceBox b;
  for (std::size_t a = 0; a < 3; ++a) {
    b.lo[a] = g.origin()[a] + cells.lo[a] * g.cell_size();
    b.hi[a] = g.origin()[a] + cells.hi[a] * g.cell_size();
    if (!part.periodic()[a]) {
      if (cells.lo[a] == 0) b.lo[a] = -inf;
      if (cells.hi[a] == g.cells()[a]) b.hi[a] = inf;
    }
  }
  return b;
}

void ConcurrentMpmSide::take_reactions(std::vector<coupling::Vec3> force) {
  reactions_ = std::move(force);
  engine_.boundary_conditions().point_forces = reactions_;
}

}  // namespace pbms::mpm
