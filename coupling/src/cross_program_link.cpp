#include "pbms/coupling/cross_program_link.hpp"

#include <algorithm>

#include "pbms/coupling/scalar_across_programs.hpp"
#include "pbms/grid/for_each_node.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::coupling {

CrossProgramLink::CrossProgramLink(MPI_Comm inter, ParticleSide& side,
                                   const grid::GridPartition& mine,
                                   const grid::GridPartition& theirs, const grid::NodeBox& band,
                                   double reach)
    : side_(side),
      particles_(&side),
      sum_(inter, mine, theirs, band),
      band_(band),
      periodic_(mine.periodic()),
      cells_(mine.grid().cells()),
      ghosts_(std::make_unique<PointGhostsAcrossPrograms>(
          inter, PointGhostsAcrossPrograms::Side::kReceiver, side.partner_box(), reach,
          side.partner_images())),
      inter_(inter) {}

CrossProgramLink::CrossProgramLink(MPI_Comm inter, ContinuumSide& side,
                                   const grid::GridPartition& mine,
                                   const grid::GridPartition& theirs, const grid::NodeBox& band,
                                   double reach)
    : side_(side),
      continuum_(&side),
      sum_(inter, mine, theirs, band),
      band_(band),
      periodic_(mine.periodic()),
      cells_(mine.grid().cells()),
      ghosts_(std::make_unique<PointGhostsAcrossPrograms>(
          inter, PointGhostsAcrossPrograms::Side::kSender, side.points_box(), reach,
          PeriodicLengths{})),
      inter_(inter) {}

// Both programs agree whether to choose the partners afresh (one number
// each way between the roots); then the receivers' boxes are swapped again
// and the points within reach sent, or the same points resent moved.
void CrossProgramLink::share_partners() {
  const double mine = side_.wants_new_partners() ? 1.0 : 0.0;
  const bool renew = !chosen_ || std::max(mine, swap_scalar(inter_, side_.comm(), mine)) > 0.0;
  chosen_ = true;
  if (particles_ != nullptr) {
    if (renew) {
      ghosts_->update_boxes(particles_->partner_box(), particles_->partner_images());
      particles_->take_partners(ghosts_->receive());
    } else {
      particles_->move_partners(ghosts_->receive());
    }
    return;
  }
  const ContinuumSide::Points p = continuum_->partner_points();
  if (renew) {
    ghosts_->update_boxes(continuum_->points_box(), PeriodicLengths{});
    ghosts_->send(p.id, p.x, p.v, p.mass);
    continuum_->partners_renewed();
  } else {
    ghosts_->resend(p.x, p.v);
  }
}

void CrossProgramLink::return_reactions() {
  if (particles_ != nullptr) {
    ghosts_->return_forces(particles_->partner_forces());
  } else {
    std::vector<Vec3> force(continuum_->partner_points().id.size(), Vec3{0.0, 0.0, 0.0});
    ghosts_->collect_forces(force);
    continuum_->take_reactions(std::move(force));
  }
}

void CrossProgramLink::sum_nodes(int first, int count) {
  const NodalRecords r = side_.nodal_records();
  sum_.sum(r.data + first, count, r.stride);
}

void CrossProgramLink::exchange_nodes(int first, int count, bool gradients) {
  const NodalRecords r = side_.nodal_records();
  const GridSide::ContactRecords c = side_.contact_records();
  sum_.copy_across(r.data + first, c.other_sums.data + first, count, r.stride);
  if (gradients) {
    sum_.copy_across(c.gradient.data, c.other_gradient.data, c.gradient.stride, c.gradient.stride);
  }
}

void CrossProgramLink::sum_holds() {
  const NodalRecords n = side_.nodal_records();
  const auto stride = static_cast<std::size_t>(n.stride);
  int held = 0;
  grid::for_each_node(n.nodes.intersected(band_), [&](const std::array<int, 3>& ijk) {
    for (std::size_t a = 0; a < 3; ++a) {
      if (periodic_[a] && ijk[a] >= cells_[a]) return;
    }
    const auto k = static_cast<std::size_t>(n.nodes.local_index(ijk));
    if (n.data[k * stride + grid::sums::kHeldAxes] > 0.0) held = 1;
  });
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, &held, 1, MPI_INT, MPI_MAX, side_.comm()),
             "MPI_Allreduce (held nodes in the band)");
  if (held == 0) return;
  const NodalRecords r = side_.held_nodes();
  sum_.sum(r.data, r.stride, r.stride);
}

}  // namespace pbms::coupling
