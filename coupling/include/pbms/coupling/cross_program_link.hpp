// The link of a split concurrent run: this program's side and the other
// program, joined by an intercommunicator. Partners go from the continuum
// ranks to the particle ranks within reach (PointGhostsAcrossPrograms),
// reactions come back the same way, and the nodal sums run between the
// ranks whose grid boxes overlap (NodalSumAcrossPrograms). Rank to rank;
// nothing passes through a root or the coupler.
#pragma once

#include <mpi.h>

#include <array>
#include <memory>

#include "pbms/coupling/coupling_link.hpp"
#include "pbms/coupling/coupling_side.hpp"
#include "pbms/coupling/nodal_sum_across_programs.hpp"
#include "pbms/coupling/point_ghosts_across_programs.hpp"
#include "pbms/grid/grid_partition.hpp"

namespace pbms::coupling {

class CrossProgramLink : public CouplingLink {
 public:
  // Collective over both programs (the ghost plan swaps boxes). `mine` and
  // `theirs` split the shared grid over this program's and the other's
  // ranks; `band` is the nodes both may touch; `reach` the pair cutoff plus
  // the DPD neighbour list's skin (partners are chosen afresh only when
  // either side has moved more than half the skin).
  // Everything passed must outlive the link.
  CrossProgramLink(MPI_Comm inter, ParticleSide& side, const grid::GridPartition& mine,
                   const grid::GridPartition& theirs, const grid::NodeBox& band, double reach);
  CrossProgramLink(MPI_Comm inter, ContinuumSide& side, const grid::GridPartition& mine,
                   const grid::GridPartition& theirs, const grid::NodeBox& band, double reach);

  void share_partners() override;
  void return_reactions() override;
  void sum_nodes(int first, int count) override;
  void exchange_nodes(int first, int count, bool gradients) override;
  // Only when a rigid group of either program holds a node of the band
  // (its held axes, summed with the nodal sums, say so alike in both
  // programs): otherwise nothing either holds reaches the other.
  void sum_holds() override;

  [[nodiscard]] const ExchangeProfile& nodal_profile() const { return sum_.profile(); }
  [[nodiscard]] const ExchangeProfile& partner_profile() const { return ghosts_->profile(); }

 private:
  GridSide& side_;
  ParticleSide* particles_ = nullptr;
  ContinuumSide* continuum_ = nullptr;
  NodalSumAcrossPrograms sum_;
  grid::NodeBox band_;
  // On periodic axes the node at index `cells` is node 0's image, summed
  // as node 0 (only when node 0 is in the band too), so it is left out of
  // the decision to swap the held nodes, which both programs must share.
  std::array<bool, 3> periodic_{};
  std::array<int, 3> cells_{};
  std::unique_ptr<PointGhostsAcrossPrograms> ghosts_;
  MPI_Comm inter_;
  bool chosen_ = false;  // partners chosen at least once
};

}  // namespace pbms::coupling
