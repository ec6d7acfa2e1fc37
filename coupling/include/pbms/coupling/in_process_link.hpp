// The link of the monolithic reference: both sides in one process, the
// partners handed over directly (every continuum point, at its images
// where the particle side asks for them), the reactions added back to
// their points and the nodal records added node by node over the nodes
// both sides hold. No band and no reach: whatever the split run leaves out
// by them shows as a difference to this.
#pragma once

#include <vector>

#include "pbms/coupling/coupling_link.hpp"
#include "pbms/coupling/coupling_side.hpp"

namespace pbms::coupling {

class InProcessLink : public CouplingLink {
 public:
  // Both sides must outlive the link.
  InProcessLink(ParticleSide& particles, ContinuumSide& continuum);

  void share_partners() override;
  void return_reactions() override;
  void sum_nodes(int first, int count) override;
  void exchange_nodes(int first, int count, bool gradients) override;
  void sum_holds() override;

 private:
  static void sum_records(const NodalRecords& a, const NodalRecords& b, int first, int count);
  // Lanes [first, first + count) of `from` into `to` (laid out on its own
  // nodes, zero where `from` has none).
  static void copy_records(const NodalRecords& from, const NodalRecords& to, int first, int count);
  ParticleSide& particles_;
  ContinuumSide& continuum_;
  std::vector<GhostPoint> partners_;
  std::vector<std::size_t> partner_point_;  // the continuum point of each partner
  std::vector<Vec3> partner_shift_;         // and the image it is at
  bool chosen_ = false;
};

}  // namespace pbms::coupling
