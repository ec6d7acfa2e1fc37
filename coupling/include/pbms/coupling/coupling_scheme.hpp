// The order of a concurrent DPD/MPM step (METHOD.md §3), and nothing else:
// which phase of which side runs when, and where the link exchanges.
// A split run has one side per program and a CrossProgramLink; the
// monolithic reference has both sides in one process and an InProcessLink,
// and the same order.
#pragma once

#include <string>
#include <vector>

#include "pbms/coupling/coupling_link.hpp"
#include "pbms/coupling/coupling_side.hpp"

namespace pbms::coupling {

class CouplingScheme {
 public:
  // The sides this process runs (one or both) and the link between them;
  // all must outlive the scheme.
  // `move` is both sides' grid::PointMove: with the midpoint move the
  // map at the midpoints crosses the link too, summed (one field) or, in
  // frictionless contact, each side's to the other.
  CouplingScheme(std::vector<GridSide*> sides, CouplingLink& link, InterfaceTreatment treatment,
                 GridFields fields = GridFields::kShared,
                 grid::PointMove move = grid::PointMove::kStepStart);

  // One step. Collective over both sides' ranks.
  void step();
  // The same, adding `part` (which part of the body this process advances)
  // to the message of a step that fails, keeping the failure's type.
  void step_naming(const std::string& part);
  // After the last step: the partners where the run ended and the particle
  // sides' forces there, so that a tallied force pass also sees the final
  // state (a step's tally sees the state before it). Collective over both
  // sides' ranks; changes no position or velocity.
  void close();

  [[nodiscard]] InterfaceTreatment treatment() const { return treatment_; }

 private:
  std::vector<GridSide*> sides_;
  CouplingLink& link_;
  InterfaceTreatment treatment_;
  GridFields fields_;
  grid::PointMove move_;
};

}  // namespace pbms::coupling
