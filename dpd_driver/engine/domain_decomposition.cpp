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
