// The spatial decomposition of the DPD box over the ranks of a driver: a
// px × py × pz grid of equal sub-boxes, each rank owning the particles
// inside its own. The grid is the one with the least sub-box surface (the
// ghost volume), among those whose sub-boxes are at least one interaction
// reach thick on every split axis, so that ghosts come from face
// neighbours only (one hop per direction, as LAMMPS' brick comm).
//
// The DPD/MPM-grid model takes another split instead: the cell boxes of an
// MPM grid's partition, so that every particle a rank owns lies in the
// rank's own cells when it is mapped to the grid.
#pragma once

#include <mpi.h>

#include <array>

#include "kernels/orthogonal_box.hpp"
#include "pbms/grid/grid_partition.hpp"

namespace pbms::dpd {

class DomainDecomposition {
 public:
  // Collective in the sense that every rank must pass the same box and
  // reach. Throws pbms::Error naming the box, reach and rank count when no
  // grid has sub-boxes thick enough.
  DomainDecomposition(MPI_Comm comm, const OrthogonalBox& box, double reach);
  // The process grid and cell boundaries of `partition` (over the ranks
  // of comm): rank r's sub-box is partition.cells_of(r) in space, so that
  // a particle the decomposition hands to a rank is one the grid solver
  // of that rank can map. On periodic axes the outermost boundaries are
  // the box's faces; on free ones the outermost ranks own everything
  // beyond (as partition.owner_of clamps). Throws pbms::Error when the
  // rank counts differ, or when a sub-box that must pass ghosts on (any
  // but the outermost on a free axis) is thinner than reach.
  DomainDecomposition(MPI_Comm comm, const OrthogonalBox& box, double reach,
                      const grid::GridPartition& partition);

  [[nodiscard]] MPI_Comm comm() const { return comm_; }
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }
  [[nodiscard]] const OrthogonalBox& box() const { return box_; }
  [[nodiscard]] const std::array<int, 3>& dims() const { return dims_; }
  [[nodiscard]] const std::array<int, 3>& coords() const { return coords_; }
  [[nodiscard]] bool split(int axis) const { return dims_[axis] > 1; }

  // This rank's sub-box: [lo, hi) on every axis, except that on a free
  // axis the first and last ranks also own everything beyond the box.
  [[nodiscard]] double sub_lo(int axis) const { return sub_lo_[axis]; }
  [[nodiscard]] double sub_hi(int axis) const { return sub_hi_[axis]; }
  // Whether this rank owns a position (assumed wrapped on periodic axes).
  [[nodiscard]] bool owns(const Vec3& x) const;
  // The neighbour rank one step down (-1) or up (+1) along an axis, or -1
  // where a free axis ends.
  [[nodiscard]] int neighbour(int axis, int direction) const;
  // The box the neighbour list sees: periodic only on the periodic axes
  // that are not split (the split ones reach their images through ghosts).
  [[nodiscard]] OrthogonalBox list_box() const;

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  OrthogonalBox box_;
  std::array<int, 3> dims_{1, 1, 1};
  std::array<int, 3> coords_{0, 0, 0};
  Vec3 sub_lo_{}, sub_hi_{};
};

}  // namespace pbms::dpd
