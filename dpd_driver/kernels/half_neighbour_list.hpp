// Half Verlet neighbour list built from a cell list: each pair within
// cutoff + skin appears once, under its lower index. The list stays valid
// until some particle has moved more than skin/2 since the build.
//
// Periodic images are resolved at build time: every entry carries the image
// shift that made the pair a minimum image, and positions are wrapped into
// the box only by build(). The force loop then needs no rounding per pair,
// r_ij = x_i - x_j + shift, however far particles drift between builds.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/dpd_particles.hpp"
#include "kernels/orthogonal_box.hpp"

namespace pbms::dpd {

class HalfNeighbourList {
 public:
  // An entry packs the neighbour index (low 27 bits) and the image shift
  // code (high 5 bits) in one word, so the force loop streams one array.
  using Entry = std::uint32_t;
  static constexpr int kIndexBits = 27;
  static constexpr std::size_t kMaxParticles = std::size_t{1} << kIndexBits;

  // Lists pairs closer than cutoff + skin (both Å). Throws pbms::Error for a
  // non-positive cutoff or a negative skin. keep_pair_ids: also store every
  // entry's two global ids (pair_ids()), 8 bytes an entry, which a run
  // without the DPD thermostat does not need.
  HalfNeighbourList(double cutoff, double skin, bool keep_pair_ids = true);

  // Wraps positions into the box on periodic axes (counting the crossings
  // in particles.image), then lists all pairs. Throws pbms::Error when a
  // periodic length is below 2 (cutoff + skin), where a particle could
  // interact with two images of another, or beyond kMaxParticles.
  //
  // In a decomposed run the particles from index `owned` on are ghosts:
  // copies of other ranks' particles, already at their image positions. The
  // list then holds every owned-owned pair once and every owned-ghost pair
  // once (under the owned particle), never a ghost-ghost pair, and has
  // `owned` rows; a rank adds forces only to its owned particles, so a pair
  // that straddles two ranks is evaluated on both (no reverse communication).
  //
  // Particles from index `partners_from` on (at or after the ghosts) are
  // another program's points (a concurrent run's partners): each of their
  // pairs is evaluated on one rank only, which the tallies must know.
  void build(DpdParticles& particles, const OrthogonalBox& box, std::size_t owned = kAllOwned,
             std::size_t partners_from = kNoPartners);
  static constexpr std::size_t kAllOwned = static_cast<std::size_t>(-1);
  static constexpr std::size_t kNoPartners = static_cast<std::size_t>(-1);

  // True when some owned particle has moved more than skin/2 since the last
  // build, so that a pair now inside the cutoff might be missing; true
  // before any build.
  [[nodiscard]] bool needs_rebuild(const DpdParticles& particles) const;
  // The largest squared displacement of an owned particle since the build, Å².
  [[nodiscard]] double max_displacement_squared(const DpdParticles& particles) const;

  [[nodiscard]] double cutoff() const { return cutoff_; }
  [[nodiscard]] double skin() const { return skin_; }
  // Rows of the list: the owned particles.
  [[nodiscard]] std::size_t particle_count() const {
    return first_.empty() ? 0 : first_.size() - 1;
  }
  [[nodiscard]] std::size_t pair_count() const { return entries_.size(); }
  // The index of the first partner at the last build (the particle count
  // when there were none).
  [[nodiscard]] std::size_t partners_from() const { return partners_from_; }
  [[nodiscard]] long build_count() const { return builds_; }
  // The owned particles' positions at the last build (wrapped): a list
  // built again from them is this one.
  [[nodiscard]] const std::vector<Vec3>& positions_at_build() const { return x_at_build_; }

  // Neighbours of particle i are entries [first(i), first(i + 1)).
  [[nodiscard]] std::size_t first(std::size_t i) const { return first_[i]; }
  [[nodiscard]] const Entry* entries() const { return entries_.data(); }
  [[nodiscard]] static std::size_t neighbour(Entry e) { return e & ((Entry{1} << kIndexBits) - 1); }
  [[nodiscard]] static int shift_code(Entry e) { return static_cast<int>(e >> kIndexBits); }
  // Added to x_i - x_j to give the separation the list was built for, Å.
  [[nodiscard]] const Vec3& shift(int code) const { return shifts_[code]; }
  [[nodiscard]] const std::array<Vec3, 27>& shifts() const { return shifts_; }
  // Entry k's two particle ids, each truncated to 32 bits, the lower in the
  // low half: the pair-noise counter words (pair_noise.hpp), fixed from one
  // build to the next, so the thermostat reads them in the order it reads
  // the entries instead of fetching id[j] per pair. Null unless kept.
  [[nodiscard]] const std::uint64_t* pair_ids() const {
    return keep_pair_ids_ ? pair_ids_.data() : nullptr;
  }
  // r_ij = x_i - x_j + shift of entry e of particle i: the separation every
  // scalar pair loop starts from (the vectorised force loop gathers its own).
  [[nodiscard]] Vec3 separation(const Vec3* x, std::size_t i, Entry e) const {
    const std::size_t j = neighbour(e);
    const Vec3& s = shifts_[shift_code(e)];
    return {x[i][0] - x[j][0] + s[0], x[i][1] - x[j][1] + s[1], x[i][2] - x[j][2] + s[2]};
  }

 private:
  // The cell grid of one build: cells per axis, edge lengths at least the
  // reach, so that a pair can only span neighbouring cells.
  struct CellGrid {
    std::array<double, 3> origin{};    // corner of cell (0, 0, 0), Å
    std::array<double, 3> inv_cell{};  // cells per Å
    std::array<int, 3> cells{};
  };
  // Wraps the periodic axes (the only place that does) and sizes the grid.
  static CellGrid fit_cell_grid(DpdParticles& particles, const OrthogonalBox& box, double reach);
  void bin_particles(const DpdParticles& particles, const CellGrid& grid);
  void set_image_shifts(const OrthogonalBox& box);
  // Fills first_ and entries_ for the first `rows` particles.
  void list_pairs(const DpdParticles& particles, const OrthogonalBox& box, const CellGrid& grid,
                  std::size_t rows, double reach_sq);
  void store_pair_ids(const DpdParticles& particles, std::size_t rows);

  double cutoff_;
  double skin_;
  long builds_ = 0;
  std::size_t partners_from_ = 0;
  std::vector<std::size_t> first_;
  std::vector<Entry> entries_;
  bool keep_pair_ids_;
  std::vector<std::uint64_t> pair_ids_;
  std::array<Vec3, 27> shifts_{};
  std::vector<Vec3> x_at_build_;
  // Cell list scratch, kept between builds to avoid reallocation.
  std::vector<int> cell_of_;
  std::vector<int> cell_start_;
  std::vector<int> in_cell_order_;
};

}  // namespace pbms::dpd
