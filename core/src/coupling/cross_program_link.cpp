#include "pbms/coupling/cross_program_link.hpp"

namespace pbms::coupling {

CrossProgramLink::CrossProgramLink(MPI_Comm inter, ParticleSide& side,
                                   const grid::GridPartition& mine,
                                   const grid::GridPartition& theirs, const grid::NodeBox& band,
                                   double reach)
    : side_(side),
      particles_(&side),
      sum_(inter, mine, theirs, band),
      ghosts_(std::make_unique<PointGhostsAcrossPrograms>(
          inter, PointGhostsAcrossPrograms::Side::kReceiver, side.partner_box(), reach,
          side.partner_images())) {}

CrossProgramLink::CrossProgramLink(MPI_Comm inter, ContinuumSide& side,
                                   const grid::GridPartition& mine,
                                   const grid::GridPartition& theirs, const grid::NodeBox& band,
                                   double reach)
    : side_(side),
      continuum_(&side),
      sum_(inter, mine, theirs, band),
      ghosts_(std::make_unique<PointGhostsAcrossPrograms>(
          inter, PointGhostsAcrossPrograms::Side::kSender, side.points_box(), reach,
          PeriodicLengths{})) {}

// The particles moved since the last step, so the receivers' boxes are
// swapped again first (one small collective over the intercommunicator).
void CrossProgramLink::share_partners() {
  if (particles_ != nullptr) {
    ghosts_->update_boxes(particles_->partner_box(), particles_->partner_images());
    particles_->take_partners(ghosts_->receive());
  } else {
    ghosts_->update_boxes(continuum_->points_box(), PeriodicLengths{});
    const ContinuumSide::Points p = continuum_->partner_points();
    ghosts_->send(p.id, p.x, p.v, p.mass);
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

}  // namespace pbms::coupling
