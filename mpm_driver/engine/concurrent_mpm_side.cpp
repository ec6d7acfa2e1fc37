#include "engine/concurrent_mpm_side.hpp"

#include <cmath>
#include <limits>

namespace pbms::mpm {

ConcurrentMpmSide::ConcurrentMpmSide(MpmEngine& engine, double dt, double partner_skin,
                                     int gas_material)
    : engine_(engine), dt_(dt), skin_(partner_skin), gas_(gas_material) {}

bool ConcurrentMpmSide::follow_points() {
  const grid::MaterialPoints& p = engine_.points();
  if (p.id != ids_) {
    ids_ = p.id;
    last_x_ = unwrapped_ = p.x;
    return false;
  }
  const grid::GridPartition& part = engine_.partition();
  const grid::RegularGrid& g = part.grid();
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t a = 0; a < 3; ++a) {
      double d = p.x[i][a] - last_x_[i][a];
      if (part.periodic()[a]) {
        const double period = g.upper()[a] - g.origin()[a];
        d -= period * std::round(d / period);
      }
      unwrapped_[i][a] += d;
    }
    last_x_[i] = p.x[i];
  }
  return true;
}

bool ConcurrentMpmSide::wants_new_partners() {
  int renew = follow_points() && !changed_ ? 0 : 1;
  const double half_skin_squared = 0.25 * skin_ * skin_;
  const auto& material = engine_.points().material;
  for (std::size_t i = 0; i < unwrapped_.size() && renew == 0; ++i) {
    if (material[i] == gas_) continue;  // no partner
    double d2 = 0.0;
    for (std::size_t a = 0; a < 3; ++a) {
      const double d = unwrapped_[i][a] - chosen_at_[i][a];
      d2 += d * d;
    }
    renew = d2 > half_skin_squared || skin_ <= 0.0 ? 1 : 0;
  }
  MPI_Allreduce(MPI_IN_PLACE, &renew, 1, MPI_INT, MPI_MAX, engine_.comm());
  return renew != 0;
}

void ConcurrentMpmSide::partners_renewed() {
  chosen_at_ = unwrapped_;
  changed_ = false;
}

void ConcurrentMpmSide::map_to_grid() {
  engine_.begin_step();
  engine_.map_to_grid(dt_);
  engine_.complete_nodal_sums();
  engine_.solver().mark_held_nodes(engine_.boundary_conditions());
}

coupling::NodalRecords ConcurrentMpmSide::nodal_records() {
  const auto s = engine_.solver().nodal_sums();
  return {s.data, s.stride, s.nodes};
}

void ConcurrentMpmSide::update_nodes() {
  engine_.update_nodes(dt_);
  holds_.reset();
}

// Asked for only when some rigid group holds a node of the band.
coupling::NodalRecords ConcurrentMpmSide::held_nodes() {
  return holds_.offer(engine_.solver().nodal_sums().nodes, [this](double* r) {
    engine_.solver().held_nodes(engine_.boundary_conditions(), r);
  });
}

void ConcurrentMpmSide::map_back() {
  if (const double* others = holds_.others()) engine_.solver().hold_nodes_of_others(others, dt_);
  engine_.map_to_points(dt_);
  engine_.complete_remap_sums();
}

// The reactions belong to this step's point order, which the migration
// changes.
void ConcurrentMpmSide::map_at_midpoints() {
  engine_.update_stress_and_map_midpoints(dt_);
}

void ConcurrentMpmSide::finish_step() {
  engine_.move_from_midpoints(dt_);
  engine_.boundary_conditions().point_forces = {};
  reactions_.clear();
  engine_.migrate();
  if (engine_.points().id != ids_) changed_ = true;
}

void ConcurrentMpmSide::choose_partner_points() const {
  const grid::MaterialPoints& p = engine_.points();
  PartnerCopy& c = partner_;
  c = PartnerCopy{};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] == gas_) continue;
    c.index.push_back(i);
    c.id.push_back(p.id[i]);
    c.x.push_back(unwrapped_[i]);
    c.v.push_back(p.v[i]);
    c.mass.push_back(p.mass[i]);
  }
}

coupling::ContinuumSide::Points ConcurrentMpmSide::partner_points() const {
  const grid::MaterialPoints& p = engine_.points();
  if (gas_ < 0) return {p.id, unwrapped_, p.v, p.mass};
  choose_partner_points();
  return {partner_.id, partner_.x, partner_.v, partner_.mass};
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
  if (gas_ < 0) {
    reactions_ = std::move(force);
  } else {
    // partner_ still lists this step's partner points (the same order).
    reactions_.assign(engine_.points().size(), {0.0, 0.0, 0.0});
    for (std::size_t k = 0; k < force.size(); ++k) reactions_[partner_.index[k]] = force[k];
  }
  if (ghost_forces_ != nullptr) {
    const grid::MaterialPoints& p = engine_.points();
    parts_.assign(p.size(), 0);
    if (!ghost_forces_->measured()) {
      for (std::size_t i = 0; i < p.size(); ++i) parts_[i] = part_of_(p.x[i]);
    }
    ghost_forces_->correct(p.id, parts_, reactions_);
  }
  engine_.boundary_conditions().point_forces = reactions_;
}

}  // namespace pbms::mpm
