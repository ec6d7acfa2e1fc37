#include "engine/domain_decomposition.hpp"

#include <fmt/format.h>

#include <limits>

#include "pbms/error.hpp"

namespace pbms::dpd {

DomainDecomposition::DomainDecomposition(MPI_Comm comm, const OrthogonalBox& box, double reach)
    : comm_(comm), box_(box) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  double best = std::numeric_limits<double>::infinity();
  for (int px = 1; px <= size_; ++px) {
    if (size_ % px != 0) continue;
    for (int py = 1; py <= size_ / px; ++py) {
      if ((size_ / px) % py != 0) continue;
      const int pz = size_ / px / py;
      const std::array<int, 3> p{px, py, pz};
      bool thick = true;
      for (int a = 0; a < 3; ++a) {
        if (p[a] > 1 && box.length(a) / p[a] < reach) thick = false;
      }
      if (!thick) continue;
      const double lx = box.length(0) / px, ly = box.length(1) / py, lz = box.length(2) / pz;
      // Surface per sub-box, ties broken towards splitting x first, for a
      // grid that does not depend on floating-point accidents.
      const double surface = lx * ly + ly * lz + lx * lz;
      if (surface < best * (1.0 - 1e-12)) {
        best = surface;
        dims_ = p;
      }
    }
  }
  if (best == std::numeric_limits<double>::infinity()) {
    throw Error(fmt::format(
        "DPD decomposition: no grid of {} ranks gives sub-boxes at least one interaction reach "
        "({:.4g} Å = cutoff + skin) thick for the box {:.4g} x {:.4g} x {:.4g} Å; use fewer "
        "ranks or a larger system",
        size_, reach, box.length(0), box.length(1), box.length(2)));
  }
  int r = rank_;
  coords_ = {r % dims_[0], (r / dims_[0]) % dims_[1], r / (dims_[0] * dims_[1])};
  for (int a = 0; a < 3; ++a) {
    const double l = box.length(a) / dims_[a];
    sub_lo_[a] = box.lo[a] + coords_[a] * l;
    sub_hi_[a] = coords_[a] + 1 == dims_[a] ? box.hi[a] : box.lo[a] + (coords_[a] + 1) * l;
  }
}

DomainDecomposition::DomainDecomposition(MPI_Comm comm, const OrthogonalBox& box, double reach,
                                         const grid::GridPartition& partition)
    : comm_(comm), box_(box) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  if (partition.ranks() != size_) {
    throw Error(fmt::format("DPD decomposition: a grid partition over {} ranks given to {} ranks",
                            partition.ranks(), size_));
  }
  dims_ = partition.dims();
  const int r = rank_;
  coords_ = {r % dims_[0], (r / dims_[0]) % dims_[1], r / (dims_[0] * dims_[1])};
  const grid::RegularGrid& g = partition.grid();
  const grid::CellBox cells = partition.cells_of(rank_);
  for (int a = 0; a < 3; ++a) {
    const auto aa = static_cast<std::size_t>(a);
    // The solver's patch starts at origin + lo h, computed the same way,
    // so a particle this rank owns is inside its patch to the last bit.
    sub_lo_[a] = g.origin()[aa] + cells.lo[aa] * g.cell_size();
    sub_hi_[a] = g.origin()[aa] + cells.hi[aa] * g.cell_size();
    if (box.periodic[aa] && coords_[aa] == 0) sub_lo_[a] = box.lo[aa];
    if (box.periodic[aa] && coords_[aa] + 1 == dims_[aa]) sub_hi_[a] = box.hi[aa];
  }
  // Ghosts travel one hop: the neighbour that passes them on must hold
  // every particle within reach of the face, which an outermost rank on a
  // free axis does whatever its thickness. Every rank checks every box, so
  // all throw together.
  for (int q = 0; q < size_; ++q) {
    const grid::CellBox c = partition.cells_of(q);
    for (int a = 0; a < 3; ++a) {
      const auto aa = static_cast<std::size_t>(a);
      if (dims_[aa] == 1) continue;
      const bool outermost = c.lo[aa] == 0 || c.hi[aa] == g.cells()[aa];
      if (!box.periodic[aa] && outermost) continue;
      const double thickness = (c.hi[aa] - c.lo[aa]) * g.cell_size();
      if (thickness < reach) {
        throw Error(fmt::format(
            "DPD decomposition: the grid partition's box of rank {} is {:.4g} Å thick along {}, "
            "less than one interaction reach ({:.4g} Å = cutoff + skin); use fewer ranks or a "
            "larger system",
            q, thickness, "xyz"[a], reach));
      }
    }
  }
}

bool DomainDecomposition::owns(const Vec3& x) const {
  for (int a = 0; a < 3; ++a) {
    if (!split(a)) continue;
    const bool first = coords_[a] == 0, last = coords_[a] + 1 == dims_[a];
    const bool free = !box_.periodic[a];
    if (x[a] < sub_lo_[a] && !(first && free)) return false;
    if (x[a] >= sub_hi_[a] && !(last && free)) return false;
  }
  return true;
}

int DomainDecomposition::neighbour(int axis, int direction) const {
  std::array<int, 3> c = coords_;
  c[axis] += direction;
  if (c[axis] < 0 || c[axis] >= dims_[axis]) {
    if (!box_.periodic[axis]) return -1;
    c[axis] = (c[axis] + dims_[axis]) % dims_[axis];
  }
  return c[0] + dims_[0] * (c[1] + dims_[1] * c[2]);
}

OrthogonalBox DomainDecomposition::list_box() const {
  OrthogonalBox b = box_;
  for (int a = 0; a < 3; ++a) b.periodic[a] = box_.periodic[a] && !split(a);
  return b;
}

}  // namespace pbms::dpd
