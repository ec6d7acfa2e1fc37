#include "kernels/shardlow_pair_order.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pbms/error.hpp"

namespace pbms::dpd {

namespace {

int mod3(int c) {
  return ((c % 3) + 3) % 3;
}

}  // namespace

ShardlowPairOrder::ShardlowPairOrder(const OrthogonalBox& box, double cutoff, double skin)
    : box_(box), list_(cutoff, skin, false) {
  const double reach = cutoff + skin;
  for (int a = 0; a < 3; ++a) {
    const double length = box.length(a);
    // The most cells wider than reach / 2.
    int n = static_cast<int>(std::ceil(2.0 * length / reach)) - 1;
    if (box.periodic[a]) n -= n % 3;
    if (n < (box.periodic[a] ? 3 : 1)) {
      throw Error(fmt::format(
          "Shardlow sweep: the periodic box length {:.4g} Å is too short for the DPD cutoff "
          "plus skin {:.4g} Å (at least 1.5 times that)",
          length, reach));
    }
    cells_[a] = n;
    width_[a] = length / n;
    // Faces away from lattice planes and from the periodic seam (see the
    // header); below half a cell, so that the cell across the seam has its
    // centre inside the box.
    offset_[a] = 0.381966011250105 * width_[a];
  }
}

void ShardlowPairOrder::build(const DpdParticles& particles, const OrthogonalBox& list_box,
                              const std::function<bool(const Vec3&)>& sweeps) {
  // The listing wraps the positions it is given; the caller's particles keep
  // theirs, and the wrap goes into each pair's shift instead.
  scratch_.x = particles.x;
  scratch_.id = particles.id;
  scratch_.image.assign(particles.size(), {0, 0, 0});
  list_.build(scratch_, list_box);

  const CellBounds bounds = keep_swept_pairs(particles, list_box, sweeps);
  sort_kept_pairs(bounds);
}

ShardlowPairOrder::CellBounds ShardlowPairOrder::keep_swept_pairs(
    const DpdParticles& particles, const OrthogonalBox& list_box,
    const std::function<bool(const Vec3&)>& sweeps) {
  kept_.clear();
  id_key_.clear();
  std::array<int, 3> low{0, 0, 0}, high{-1, -1, -1};
  const HalfNeighbourList::Entry* entries = list_.entries();
  for (std::size_t row = 0; row < list_.particle_count(); ++row) {
    for (std::size_t k = list_.first(row); k < list_.first(row + 1); ++k) {
      ShardlowPair pair = lower_id_first(particles, row, entries[k]);
      const Vec3 centre = place_midpoint(particles, list_box, pair);
      if (!sweeps(centre)) continue;
      if (kept_.empty()) {
        low = high = pair.cell;
      } else {
        for (int ax = 0; ax < 3; ++ax) {
          low[ax] = std::min(low[ax], pair.cell[ax]);
          high[ax] = std::max(high[ax], pair.cell[ax]);
        }
      }
      kept_.push_back(pair);
      // Ids fit in 32 bits (check_pair_noise_ids).
      id_key_.push_back(static_cast<std::uint64_t>(particles.id[pair.i]) << 32 |
                        static_cast<std::uint64_t>(particles.id[pair.j]));
    }
  }
  return {low, high};
}

// The pair of list entry e of `row`, its shift taken back from the wrapped
// scratch positions to the caller's.
ShardlowPair ShardlowPairOrder::lower_id_first(const DpdParticles& particles, std::size_t row,
                                               HalfNeighbourList::Entry e) const {
  std::size_t a = row, b = HalfNeighbourList::neighbour(e);
  const Vec3& s = list_.shift(HalfNeighbourList::shift_code(e));
  ShardlowPair pair{a, b, {}, {}};
  for (int ax = 0; ax < 3; ++ax) {
    pair.shift[ax] =
        s[ax] + (scratch_.x[a][ax] - particles.x[a][ax]) - (scratch_.x[b][ax] - particles.x[b][ax]);
  }
  if (particles.id[a] > particles.id[b]) {
    std::swap(a, b);
    pair = {a, b, {-pair.shift[0], -pair.shift[1], -pair.shift[2]}, {}};
  }
  return pair;
}

// Sets pair.cell to the cell of the pair's midpoint and returns that cell's
// centre.
Vec3 ShardlowPairOrder::place_midpoint(const DpdParticles& particles, const OrthogonalBox& list_box,
                                       ShardlowPair& pair) const {
  const Vec3 d = pair.separation(particles.x.data());
  Vec3 centre{};
  for (int ax = 0; ax < 3; ++ax) {
    double m = particles.x[pair.i][ax] - 0.5 * d[ax];
    const double lo = box_.lo[ax];
    if (list_box.periodic[ax]) m -= box_.length(ax) * std::floor((m - lo) / box_.length(ax));
    int c = static_cast<int>(std::floor((m - lo - offset_[ax]) / width_[ax]));
    if (list_box.periodic[ax]) c = (c % cells_[ax] + cells_[ax]) % cells_[ax];
    pair.cell[ax] = c;
    centre[ax] = lo + offset_[ax] + (c + 0.5) * width_[ax];
  }
  return centre;
}

// A counting sort into buckets of (colour, cell), then each bucket by ids.
void ShardlowPairOrder::sort_kept_pairs(const CellBounds& bounds) {
  const std::array<int, 3>& low = bounds.low;
  const std::array<int, 3>& high = bounds.high;
  std::array<std::size_t, 3> span{};
  for (int ax = 0; ax < 3; ++ax) span[ax] = static_cast<std::size_t>(high[ax] - low[ax] + 1);
  const std::size_t cells = span[0] * span[1] * span[2];
  bucket_of_.resize(kept_.size());
  count_.assign(kColours * cells + 1, 0);
  for (std::size_t k = 0; k < kept_.size(); ++k) {
    const auto& c = kept_[k].cell;
    int colour = 0;
    for (int ax = 2; ax >= 0; --ax) colour = 3 * colour + mod3(c[ax]);
    std::size_t dense = 0;
    for (int ax = 2; ax >= 0; --ax) {
      dense = dense * span[ax] + static_cast<std::size_t>(c[ax] - low[ax]);
    }
    bucket_of_[k] = static_cast<std::uint64_t>(colour) * cells + dense;
    ++count_[bucket_of_[k] + 1];
  }
  for (std::size_t q = 0; q + 1 < count_.size(); ++q) count_[q + 1] += count_[q];
  begin_.fill(kept_.size());
  for (std::size_t colour = 0; colour < kColours; ++colour) begin_[colour] = count_[colour * cells];
  slot_.resize(kept_.size());
  for (std::size_t k = 0; k < kept_.size(); ++k) slot_[count_[bucket_of_[k]]++] = k;
  pairs_.resize(kept_.size());
  for (std::size_t first = 0; first < slot_.size();) {
    std::size_t last = first + 1;
    while (last < slot_.size() && bucket_of_[slot_[last]] == bucket_of_[slot_[first]]) ++last;
    std::sort(slot_.begin() + static_cast<std::ptrdiff_t>(first),
              slot_.begin() + static_cast<std::ptrdiff_t>(last),
              [&](std::size_t x, std::size_t y) { return id_key_[x] < id_key_[y]; });
    for (std::size_t k = first; k < last; ++k) pairs_[k] = kept_[slot_[k]];
    first = last;
  }
}

std::span<const ShardlowPair> ShardlowPairOrder::colour(int c) const {
  const auto b = begin_[static_cast<std::size_t>(c)];
  return std::span<const ShardlowPair>(pairs_).subspan(b,
                                                       begin_[static_cast<std::size_t>(c) + 1] - b);
}

}  // namespace pbms::dpd
