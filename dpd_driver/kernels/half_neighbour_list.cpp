#include "kernels/half_neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "kernels/periodic_wrap.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

namespace {

// The cells a particle in cell c of an axis with n cells must search.
// Fewer than three periodic cells would visit one cell twice, so such an
// axis searches each cell once.
int neighbour_cells(int c, int n, bool periodic, std::array<int, 3>& out) {
  if (periodic && n < 3) {
    for (int k = 0; k < n; ++k) out[k] = k;
    return n;
  }
  int count = 0;
  for (int d = -1; d <= 1; ++d) {
    int k = c + d;
    if (periodic) {
      k = (k + n) % n;
    } else if (k < 0 || k >= n) {
      continue;
    }
    out[count++] = k;
  }
  return count;
}

}  // namespace

HalfNeighbourList::HalfNeighbourList(double cutoff, double skin, bool keep_pair_ids)
    : cutoff_(cutoff), skin_(skin), keep_pair_ids_(keep_pair_ids) {
  if (!(cutoff > 0.0)) throw Error("neighbour list: cutoff must be > 0 Å");
  if (!(skin >= 0.0)) throw Error("neighbour list: skin must be >= 0 Å");
}

void HalfNeighbourList::build(DpdParticles& particles, const OrthogonalBox& box, std::size_t owned,
                              std::size_t partners_from) {
  const std::size_t n = particles.size();
  const std::size_t rows = std::min(owned, n);
  partners_from_ = std::min(partners_from, n);
  if (n > kMaxParticles) {
    throw Error("neighbour list: " + std::to_string(n) + " particles on one rank, at most " +
                std::to_string(kMaxParticles));
  }
  const double reach = cutoff_ + skin_;
  const double reach_sq = reach * reach;

  const CellGrid grid = fit_cell_grid(particles, box, reach);
  bin_particles(particles, grid);
  set_image_shifts(box);
  list_pairs(particles, box, grid, rows, reach_sq);
  if (keep_pair_ids_) store_pair_ids(particles, rows);
  x_at_build_.assign(particles.x.begin(), particles.x.begin() + static_cast<std::ptrdiff_t>(rows));
  ++builds_;
}

HalfNeighbourList::CellGrid HalfNeighbourList::fit_cell_grid(DpdParticles& particles,
                                                             const OrthogonalBox& box,
                                                             double reach) {
  const std::size_t n = particles.size();
  CellGrid grid;
  for (int a = 0; a < 3; ++a) {
    double lo = box.lo[a];
    double extent = box.length(a);
    if (box.periodic[a]) {
      if (!(extent >= 2.0 * reach)) {
        throw Error("neighbour list: periodic box length " + std::to_string(extent) +
                    " Å on axis " + std::to_string(a) + " is below 2 (cutoff + skin) = " +
                    std::to_string(2.0 * reach) + " Å; replicate the box");
      }
      // Wrapping happens here and only here; see the header.
      wrap_axis(particles, box, a, n);
    } else {
      // A free axis bins the particles where they are, inside the box or not.
      double hi = lo;
      if (n > 0) {
        lo = hi = particles.x[0][a];
        for (std::size_t i = 1; i < n; ++i) {
          lo = std::min(lo, particles.x[i][a]);
          hi = std::max(hi, particles.x[i][a]);
        }
      }
      extent = hi - lo;
    }
    grid.origin[a] = lo;
    grid.cells[a] = std::max(1, static_cast<int>(extent / reach));
    // Cap the grid of a sparse free axis: more cells than particles only costs.
    const int cap = static_cast<int>(std::cbrt(static_cast<double>(n))) + 3;
    if (!box.periodic[a]) grid.cells[a] = std::min(grid.cells[a], cap);
    grid.inv_cell[a] = extent > 0.0 ? grid.cells[a] / extent : 0.0;
  }
  return grid;
}

// A counting sort, so that the pair search reads each cell's particles from
// one contiguous run of in_cell_order_.
void HalfNeighbourList::bin_particles(const DpdParticles& particles, const CellGrid& grid) {
  const std::size_t n = particles.size();
  const std::array<int, 3> cells = grid.cells;  // not re-read after each store to an int
  const int cell_count = cells[0] * cells[1] * cells[2];
  cell_of_.resize(n);
  cell_start_.assign(static_cast<std::size_t>(cell_count) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    int c[3];
    for (int a = 0; a < 3; ++a) {
      c[a] = std::clamp(static_cast<int>((particles.x[i][a] - grid.origin[a]) * grid.inv_cell[a]),
                        0, cells[a] - 1);
    }
    cell_of_[i] = c[0] + cells[0] * (c[1] + cells[1] * c[2]);
    ++cell_start_[cell_of_[i] + 1];
  }
  for (int c = 0; c < cell_count; ++c) cell_start_[c + 1] += cell_start_[c];
  in_cell_order_.resize(n);
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) in_cell_order_[fill[cell_of_[i]]++] = static_cast<int>(i);
}

void HalfNeighbourList::set_image_shifts(const OrthogonalBox& box) {
  for (int code = 0; code < 27; ++code) {
    const int s[3] = {code % 3 - 1, (code / 3) % 3 - 1, code / 9 - 1};
    for (int a = 0; a < 3; ++a) shifts_[code][a] = box.periodic[a] ? s[a] * box.length(a) : 0.0;
  }
}

void HalfNeighbourList::list_pairs(const DpdParticles& particles, const OrthogonalBox& box,
                                   const CellGrid& grid, std::size_t rows, double reach_sq) {
  // A copy, not re-read after each push_back.
  const std::array<int, 3> cells = grid.cells;
  first_.resize(rows + 1);
  entries_.clear();
  for (std::size_t i = 0; i < rows; ++i) {
    first_[i] = entries_.size();
    const Vec3 xi = particles.x[i];
    const int ci = cell_of_[i];
    const int c[3] = {ci % cells[0], (ci / cells[0]) % cells[1], ci / (cells[0] * cells[1])};
    std::array<int, 3> near[3];
    int near_count[3];
    for (int a = 0; a < 3; ++a)
      near_count[a] = neighbour_cells(c[a], cells[a], box.periodic[a], near[a]);
    for (int kz = 0; kz < near_count[2]; ++kz) {
      for (int ky = 0; ky < near_count[1]; ++ky) {
        for (int kx = 0; kx < near_count[0]; ++kx) {
          const int cell = near[0][kx] + cells[0] * (near[1][ky] + cells[1] * near[2][kz]);
          for (int k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
            const auto j = static_cast<std::size_t>(in_cell_order_[k]);
            if (j <= i) continue;  // ghosts (j >= rows) all come after i
            double d2 = 0.0;
            int code = 0;
            int stride = 1;
            for (int a = 0; a < 3; ++a) {
              double d = xi[a] - particles.x[j][a];
              int s = 0;
              if (box.periodic[a]) {
                const double half = 0.5 * box.length(a);
                if (d > half) s = -1;
                if (d < -half) s = 1;
                d += s * box.length(a);
              }
              d2 += d * d;
              code += (s + 1) * stride;
              stride *= 3;
            }
            if (d2 < reach_sq) {
              entries_.push_back(static_cast<Entry>(j) | (static_cast<Entry>(code) << kIndexBits));
            }
          }
        }
      }
    }
  }
  first_[rows] = entries_.size();
}

void HalfNeighbourList::store_pair_ids(const DpdParticles& particles, std::size_t rows) {
  pair_ids_.resize(entries_.size());
  for (std::size_t i = 0; i < rows; ++i) {
    const auto id_i = static_cast<std::uint32_t>(particles.id[i]);
    for (std::size_t k = first_[i]; k < first_[i + 1]; ++k) {
      const auto id_j = static_cast<std::uint32_t>(particles.id[neighbour(entries_[k])]);
      pair_ids_[k] = (std::uint64_t{std::max(id_i, id_j)} << 32) | std::min(id_i, id_j);
    }
  }
}

bool HalfNeighbourList::needs_rebuild(const DpdParticles& particles) const {
  if (builds_ == 0 || particles.size() < x_at_build_.size()) return true;
  return max_displacement_squared(particles) > 0.25 * skin_ * skin_;
}

double HalfNeighbourList::max_displacement_squared(const DpdParticles& particles) const {
  double max_sq = 0.0;
  for (std::size_t i = 0; i < x_at_build_.size(); ++i) {
    const double dx = particles.x[i][0] - x_at_build_[i][0];
    const double dy = particles.x[i][1] - x_at_build_[i][1];
    const double dz = particles.x[i][2] - x_at_build_[i][2];
    max_sq = std::max(max_sq, dx * dx + dy * dy + dz * dz);
  }
  return max_sq;
}

}  // namespace pbms::dpd
