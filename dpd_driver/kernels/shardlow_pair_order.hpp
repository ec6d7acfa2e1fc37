// The order in which a Shardlow sweep (shardlow_sweep.hpp) updates pairs,
// chosen so that the sweep gives the same result on any number of ranks.
//
// Pair updates in a sweep do not commute, so the order must not depend on
// how the particles are split. Each pair within the list reach (cutoff +
// skin) belongs to the cell of a fixed global grid that holds its midpoint;
// cells are coloured by (c mod 3) per axis, 27 colours, and the sweep runs
// colour after colour. Cells are wider than half the reach, so the
// particles of one cell's pairs lie within reach/2 of it and two cells of
// one colour, two cells apart, never share a particle: within a colour,
// cells commute exactly and may run on different ranks at once. Within a
// cell, pairs go by (lower id, higher id). The cell counts are multiples of
// 3 on periodic axes, so that the colouring has no seam across the boundary.
//
// The order is built when the neighbour lists are (the engine decides that
// over all ranks, so on the same steps for any decomposition) and kept
// until the next build, like a Verlet list: a pair is swept only while it
// is closer than the cutoff, and no pair outside the reach can come that
// close before the next build.
//
// The grid is shifted by 0.382 of a cell (the golden section) from the box
// origin. A pair whose midpoint lies on a face falls in one cell or the
// other by the last bit of its coordinates, which differ between ranks at
// round-off (ghost images carry x ± L); in a perfect crystal many midpoints
// lie on lattice planes, and unshifted faces would sit on them and on the
// periodic seam. Shifted, a midpoint is that close to a face only by chance.
//
// A decomposed run sweeps the cells whose centre its sub-box owns; it needs
// the particles within w/2 + reach/2 < reach of its sub-box (w < reach
// always), which its ghosts hold, and must hand the ghosts' new velocities
// back to their owners between colours (DpdEngine does).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "kernels/dpd_particles.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/orthogonal_box.hpp"

namespace pbms::dpd {

struct ShardlowPair {
  std::size_t i = 0, j = 0;  // local indices, id[i] < id[j]
  // x_i - x_j + shift is the separation of the images that interact, with
  // the positions as the caller holds them (not wrapped between builds).
  Vec3 shift{};
  std::array<int, 3> cell{};  // of the midpoint (wrapped on the list's periodic axes)

  [[nodiscard]] Vec3 separation(const Vec3* x) const {
    return {x[i][0] - x[j][0] + shift[0], x[i][1] - x[j][1] + shift[1],
            x[i][2] - x[j][2] + shift[2]};
  }
};

class ShardlowPairOrder {
 public:
  static constexpr int kColours = 27;

  // The cell grid over the global box, for pairs closer than cutoff + skin
  // (Å). Throws pbms::Error when a periodic length is at most 1.5 reaches.
  ShardlowPairOrder(const OrthogonalBox& box, double cutoff, double skin);

  // Orders the pairs within the reach among all of `particles` (owned and
  // ghosts) whose midpoint cell has a centre `sweeps(centre)` accepts.
  // Positions are read, not changed. list_box: periodic on the axes whose
  // images come from shifts rather than ghosts (DomainDecomposition::
  // list_box; the box itself on one rank). Call it whenever the caller's
  // neighbour list is rebuilt (positions freshly wrapped, ghosts new).
  void build(const DpdParticles& particles, const OrthogonalBox& list_box,
             const std::function<bool(const Vec3&)>& sweeps);

  [[nodiscard]] std::span<const ShardlowPair> colour(int c) const;
  [[nodiscard]] std::size_t pair_count() const { return pairs_.size(); }
  [[nodiscard]] const std::array<int, 3>& cells() const { return cells_; }
  [[nodiscard]] const Vec3& cell_width() const { return width_; }

 private:
  // The smallest box of cells that holds every kept pair's cell.
  struct CellBounds {
    std::array<int, 3> low{};
    std::array<int, 3> high{};
  };
  // Fills kept_ and id_key_ from the list, in list order.
  CellBounds keep_swept_pairs(const DpdParticles& particles, const OrthogonalBox& list_box,
                              const std::function<bool(const Vec3&)>& sweeps);
  [[nodiscard]] ShardlowPair lower_id_first(const DpdParticles& particles, std::size_t row,
                                            HalfNeighbourList::Entry e) const;
  Vec3 place_midpoint(const DpdParticles& particles, const OrthogonalBox& list_box,
                      ShardlowPair& pair) const;
  // Fills pairs_ and begin_ from kept_.
  void sort_kept_pairs(const CellBounds& bounds);

  OrthogonalBox box_;
  std::array<int, 3> cells_{};
  Vec3 width_{};
  Vec3 offset_{};  // of the first face from box.lo, Å
  HalfNeighbourList list_;
  DpdParticles scratch_;  // positions and ids, wrapped by the listing
  std::vector<ShardlowPair> kept_;
  std::vector<std::uint64_t> bucket_of_, id_key_;
  std::vector<std::size_t> count_, slot_;
  std::vector<ShardlowPair> pairs_;
  std::array<std::size_t, kColours + 1> begin_{};
};

}  // namespace pbms::dpd
