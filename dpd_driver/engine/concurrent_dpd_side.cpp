#include "engine/concurrent_dpd_side.hpp"

#include <algorithm>
#include <limits>

namespace pbms::dpd {

ConcurrentDpdSide::ConcurrentDpdSide(DpdEngine& engine, DpdGridStep& grid, int partner_type)
    : engine_(engine), grid_(grid), partner_type_(partner_type) {}

coupling::NodalRecords ConcurrentDpdSide::nodal_records() {
  const auto s = grid_.nodal_sums();
  return {s.data, s.stride, s.nodes};
}

// Around this rank's particles, except along axes the neighbour list wraps
// (periodic and not split over ranks): there every point is a candidate,
// and the list finds the image within the cutoff itself.
coupling::SpaceBox ConcurrentDpdSide::partner_box() const {
  const OrthogonalBox list_box = engine_.domain().list_box();
  constexpr double inf = std::numeric_limits<double>::infinity();
  coupling::SpaceBox b{{inf, inf, inf}, {-inf, -inf, -inf}};
  const DpdParticles& p = engine_.particles();
  for (std::size_t i = 0; i < engine_.owned(); ++i) {
    for (std::size_t a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], p.x[i][a]);
      b.hi[a] = std::max(b.hi[a], p.x[i][a]);
    }
  }
  for (std::size_t a = 0; a < 3; ++a) {
    if (list_box.periodic[a]) {
      b.lo[a] = list_box.lo[a];
      b.hi[a] = list_box.hi[a];
    }
  }
  return b;
}

// Images only along periodic axes the list does not wrap (split over ranks).
coupling::PeriodicLengths ConcurrentDpdSide::partner_images() const {
  const OrthogonalBox& box = engine_.domain().box();
  const OrthogonalBox list_box = engine_.domain().list_box();
  coupling::PeriodicLengths out;
  for (std::size_t a = 0; a < 3; ++a) {
    if (box.periodic[a] && !list_box.periodic[a]) out.length[a] = box.length(static_cast<int>(a));
  }
  return out;
}

void ConcurrentDpdSide::unpack(const std::vector<coupling::GhostPoint>& partners) {
  x_.resize(partners.size());
  v_.resize(partners.size());
  id_.resize(partners.size());
  for (std::size_t k = 0; k < partners.size(); ++k) {
    x_[k] = partners[k].x;
    v_[k] = partners[k].v;
    id_[k] = partners[k].id;
  }
}

void ConcurrentDpdSide::take_partners(const std::vector<coupling::GhostPoint>& partners) {
  unpack(partners);
  engine_.set_partners(x_, v_, id_, partner_type_);
}

void ConcurrentDpdSide::move_partners(const std::vector<coupling::GhostPoint>& partners) {
  unpack(partners);
  engine_.move_partners(x_, v_);
}

std::vector<coupling::Vec3> ConcurrentDpdSide::partner_forces() const {
  return engine_.partner_forces();
}

void ConcurrentDpdSide::update_nodes() {
  grid_.update_nodes();
  holds_.reset();
}

// Asked for only when some rigid group holds a node of the band.
coupling::NodalRecords ConcurrentDpdSide::held_nodes() {
  return holds_.offer(grid_.nodal_sums().nodes, [this](double* r) { grid_.held_nodes(r); });
}

void ConcurrentDpdSide::map_back() {
  if (const double* others = holds_.others()) grid_.hold_nodes_of_others(others);
  grid_.map_back();
}

}  // namespace pbms::dpd
