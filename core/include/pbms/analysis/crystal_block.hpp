// A crystal block's edges measured along its own axes (the inclusion's cube,
// seed §6.2.1: V is the product of the cube's three edges).
//
// A free block in a gas turns as a whole: it keeps the spin it had when it
// was equilibrated alone, and the grid it shares with the gas passes torque
// on to it. Edges read along the box's axes then mix the turn into the
// volume. A cube that started 2° off the axes had its "outermost plane",
// taken as the particles near the extreme coordinate, cut down to the
// particles along one edge of the face (44 to 126 of its 221), and a further
// turn of 5° read as a 7 % swelling at 5 GPa. Here each particle is given
// its site on the block's own lattice once, at the start; each sample finds
// the rotation that best carries those sites onto the particles (Kabsch) and
// measures the outermost whole planes along the turned axes.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace pbms::analysis {

using BlockPoint = std::array<double, 3>;

struct BlockSites {
  // Per particle: its site on a simple cubic lattice of the plane spacing in
  // the block's frame (an fcc crystal's sites are a subset), in spacings.
  std::vector<std::array<int, 3>> index;
  // Per axis: the lowest and highest index of a whole face plane.
  std::array<std::array<int, 2>, 3> faces{};
  // The mean of index × spacing over the block, so that the sites' offsets
  // from it sum to zero.
  BlockPoint centre{};
  double spacing = 0.0;

  // The site's offset from the block's centre in the block's frame, Å.
  [[nodiscard]] BlockPoint offset(std::size_t particle) const;
};

// Fits the block's lattice to `x` (one block, every particle): the frame
// that carries a lattice of `plane_spacing` best onto the particles, and
// each particle's site in it. The fit grows from the centre outwards, so a
// block turned from the box's axes is found (tested to 15°; the cubes in a
// gas leave their equilibration turned by 0.7–2°). A face
// plane is the outermost plane holding at least half the block's median
// plane count, so that adatoms on a face do not stand for it. Throws
// pbms::Error for fewer than 8 particles or no whole plane along an axis.
[[nodiscard]] BlockSites fit_block_sites(const std::vector<BlockPoint>& x, double plane_spacing);

// The sums that one share of the block's particles contributes to a
// sample. Shares held on different ranks add element-wise (one reduction),
// since the sites' offsets sum to zero over the whole block.
struct BlockSums {
  // [0, 9): Σ offset ⊗ x (row i, column j: Σ offset_i x_j);
  // [9, 33): per face (lo x, hi x, lo y, ...): Σx, Σy, Σz, count.
  static constexpr std::size_t kSize = 33;
  std::array<double, kSize> sums{};

  void add(const BlockSites& sites, std::size_t particle, const BlockPoint& x);
};

struct BlockEdges {
  // Along the block's own axes: the distance between the two face planes'
  // mean positions, scaled by (n + 1)/n for n plane spacings between them,
  // so that an edge spans half a spacing beyond each face, as the crystal's
  // volume per site does.
  std::array<double, 3> edge{};
  double volume = 0.0;
  double rotation_deg = 0.0;  // the block's turn from the box's axes
};

// Throws pbms::Error when a face plane has no particle in the sums.
[[nodiscard]] BlockEdges block_edges(const BlockSites& sites, const BlockSums& total);

// The proper rotation R (row-major) that best carries centred sites s onto
// centred positions y, from H = Σ s ⊗ y (row-major): Kabsch's solution,
// minimising Σ |R s − y|².
[[nodiscard]] std::array<double, 9> best_rotation(const std::array<double, 9>& covariance);

}  // namespace pbms::analysis
