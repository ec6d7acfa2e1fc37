#include "pbms/coupling/in_process_link.hpp"

#include "pbms/grid/for_each_node.hpp"

namespace pbms::coupling {

InProcessLink::InProcessLink(ParticleSide& particles, ContinuumSide& continuum)
    : particles_(particles), continuum_(continuum) {}

// As between programs, the partners are chosen afresh only when either
// side has moved half the skin, so that the DPD side keeps its list: the
// same algorithm, one process.
void InProcessLink::share_partners() {
  const bool a = particles_.wants_new_partners();
  const bool b = continuum_.wants_new_partners();
  const ContinuumSide::Points p = continuum_.partner_points();
  if (chosen_ && !a && !b) {
    for (std::size_t k = 0; k < partners_.size(); ++k) {
      const std::size_t i = partner_point_[k];
      for (std::size_t c = 0; c < 3; ++c) partners_[k].x[c] = p.x[i][c] + partner_shift_[k][c];
      partners_[k].v = p.v[i];
    }
    particles_.move_partners(partners_);
    return;
  }
  const PeriodicLengths images = particles_.partner_images();
  partners_.clear();
  partner_point_.clear();
  partner_shift_.clear();
  for (std::size_t i = 0; i < p.id.size(); ++i) {
    for (int sz = -1; sz <= 1; ++sz)
      for (int sy = -1; sy <= 1; ++sy)
        for (int sx = -1; sx <= 1; ++sx) {
          const std::array<int, 3> s{sx, sy, sz};
          bool ok = true;
          Vec3 shift{};
          for (std::size_t c = 0; c < 3; ++c) {
            if (s[c] != 0 && images.length[c] <= 0.0) ok = false;
            shift[c] = s[c] * images.length[c];
          }
          if (!ok) continue;
          partners_.push_back({p.id[i],
                               {p.x[i][0] + shift[0], p.x[i][1] + shift[1], p.x[i][2] + shift[2]},
                               p.v[i],
                               p.mass[i]});
          partner_point_.push_back(i);
          partner_shift_.push_back(shift);
        }
  }
  particles_.take_partners(partners_);
  continuum_.partners_renewed();
  chosen_ = true;
}

void InProcessLink::return_reactions() {
  const std::vector<Vec3> on_partner = particles_.partner_forces();
  std::vector<Vec3> force(continuum_.partner_points().id.size(), Vec3{0.0, 0.0, 0.0});
  for (std::size_t k = 0; k < on_partner.size(); ++k) {
    for (std::size_t a = 0; a < 3; ++a) force[partner_point_[k]][a] += on_partner[k][a];
  }
  continuum_.take_reactions(std::move(force));
}

void InProcessLink::sum_nodes(int first, int count) {
  sum_records(particles_.nodal_records(), continuum_.nodal_records(), first, count);
}

void InProcessLink::exchange_nodes(int first, int count, bool gradients) {
  const GridSide::ContactRecords a = particles_.contact_records();
  const GridSide::ContactRecords b = continuum_.contact_records();
  copy_records(particles_.nodal_records(), b.other_sums, first, count);
  copy_records(continuum_.nodal_records(), a.other_sums, first, count);
  if (!gradients) return;
  copy_records(a.gradient, b.other_gradient, 0, a.gradient.stride);
  copy_records(b.gradient, a.other_gradient, 0, b.gradient.stride);
}

void InProcessLink::sum_holds() {
  const NodalRecords a = particles_.held_nodes();
  sum_records(a, continuum_.held_nodes(), 0, a.stride);
}

void InProcessLink::sum_records(const NodalRecords& a, const NodalRecords& b, int first,
                                int count) {
  const auto stride_a = static_cast<std::size_t>(a.stride);
  const auto stride_b = static_cast<std::size_t>(b.stride);
  grid::for_each_node(a.nodes.intersected(b.nodes), [&](const std::array<int, 3>& ijk) {
    double* ra = a.data + static_cast<std::size_t>(a.nodes.local_index(ijk)) * stride_a;
    double* rb = b.data + static_cast<std::size_t>(b.nodes.local_index(ijk)) * stride_b;
    for (int c = first; c < first + count; ++c) ra[c] = rb[c] = ra[c] + rb[c];
  });
}

void InProcessLink::copy_records(const NodalRecords& from, const NodalRecords& to, int first,
                                 int count) {
  const auto stride_from = static_cast<std::size_t>(from.stride);
  const auto stride_to = static_cast<std::size_t>(to.stride);
  const auto n = static_cast<std::size_t>(to.nodes.count());
  for (std::size_t k = 0; k < n; ++k) {
    for (int c = first; c < first + count; ++c) to.data[k * stride_to + c] = 0.0;
  }
  grid::for_each_node(from.nodes.intersected(to.nodes), [&](const std::array<int, 3>& ijk) {
    const double* f =
        from.data + static_cast<std::size_t>(from.nodes.local_index(ijk)) * stride_from;
    double* t = to.data + static_cast<std::size_t>(to.nodes.local_index(ijk)) * stride_to;
    for (int c = first; c < first + count; ++c) t[c] = f[c];
  });
}

}  // namespace pbms::coupling
