// What crosses between the two sides of a concurrent step: the MPM points
// the DPD particles pair with, the reactions on them, and the nodal sums.
// CrossProgramLink does it between two programs rank to rank;
// InProcessLink does it within one process that holds both sides (the
// monolithic reference the split run must reproduce).
#pragma once

namespace pbms::coupling {

class CouplingLink {
 public:
  virtual ~CouplingLink() = default;
  // The continuum's points to the particle side as this step's partners.
  virtual void share_partners() = 0;
  // The partners' pair forces back to the continuum as reactions.
  virtual void return_reactions() = 0;
  // Lanes [first, first + count) of both sides' nodal records become their
  // sum on the nodes both hold.
  virtual void sum_nodes(int first, int count) = 0;
  // GridFields::kFrictionlessContact: lanes [first, first + count) of each
  // side's nodal records become the other side's other_sums (zero on the
  // nodes it does not reach), and with `gradients` its mass gradient the
  // other's other_gradient.
  virtual void exchange_nodes(int first, int count, bool gradients) = 0;
  // Both sides' held_nodes records become their sum on the nodes both hold,
  // so that each holds what the other holds.
  virtual void sum_holds() = 0;
};

}  // namespace pbms::coupling
