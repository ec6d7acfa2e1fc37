#include "pbms/coupling/coupling_scheme.hpp"

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::coupling {

CouplingScheme::CouplingScheme(std::vector<GridSide*> sides, CouplingLink& link,
                               InterfaceTreatment treatment, GridFields fields,
                               grid::PointMove move)
    : sides_(std::move(sides)), link_(link), treatment_(treatment), fields_(fields), move_(move) {}

void CouplingScheme::step() {
  if (treatment_ != InterfaceTreatment::kNone) link_.share_partners();
  for (GridSide* s : sides_) s->compute_forces();
  if (treatment_ == InterfaceTreatment::kMomentumConserving) link_.return_reactions();
  for (GridSide* s : sides_) s->map_to_grid();
  const bool contact = fields_ == GridFields::kFrictionlessContact;
  if (contact) {
    // Each side keeps its own field and sees the other's mass, momentum and
    // force (the lanes before the held axes); only the holds add.
    link_.exchange_nodes(grid::sums::kMass, grid::sums::kHeldAxes - grid::sums::kMass, true);
    link_.sum_nodes(grid::sums::kHeldAxes, 1);
  } else {
    link_.sum_nodes(grid::sums::kMass, grid::sums::kStride);  // mass, momentum, force, holds
  }
  for (GridSide* s : sides_) s->update_nodes();
  link_.sum_holds();
  for (GridSide* s : sides_) s->map_back();
  if (contact) {
    link_.exchange_nodes(grid::sums::kMomentum, grid::sums::kVector, false);
  } else {
    link_.sum_nodes(grid::sums::kMomentum, grid::sums::kVector);  // the remapped momentum
  }
  for (GridSide* s : sides_) s->map_at_midpoints();
  if (move_ == grid::PointMove::kMidpoint) {  // mass and momentum at the midpoints
    if (contact) {
      link_.exchange_nodes(grid::sums::kMass, 1 + grid::sums::kVector, false);
    } else {
      link_.sum_nodes(grid::sums::kMass, 1 + grid::sums::kVector);
    }
  }
  for (GridSide* s : sides_) s->finish_step();
}

void CouplingScheme::close() {
  if (treatment_ != InterfaceTreatment::kNone) link_.share_partners();
  for (GridSide* s : sides_) s->compute_forces();
}

void CouplingScheme::step_naming(const std::string& part) {
  try {
    step();
  } catch (const StageFailure& e) {
    throw StageFailure(fmt::format("{}, in {}", e.what(), part));
  } catch (const Error& e) {
    throw Error(fmt::format("{}, in {}", e.what(), part));
  }
}

}  // namespace pbms::coupling
