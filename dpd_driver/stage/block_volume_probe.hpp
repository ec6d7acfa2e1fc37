// The volume of a block of DPD particles (the inclusion's cube, seed §6.2.1:
// V is the product of its three edges). Along each axis the edge is the
// distance between the mean positions of the block's two outermost lattice
// planes, chosen at the start, scaled by (d0 + a/2) / d0 so that it spans
// half a plane spacing beyond each plane as the crystal does. The planes'
// means take out the thermal motion that single outermost particles have.
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/coupling/concurrent_probes.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::dpd {

class BlockVolumeProbe {
 public:
  // Collective. `mask`: the block's group; `a`: its lattice constant;
  // `now`: this rank's particles at unwrapped positions.
  BlockVolumeProbe(MPI_Comm comm, const coupling::VolumeProbe& probe, std::uint32_t mask, double a,
                   const coupling::ParticleView& now);

  // Collective over the part's ranks.
  void sample(double t, const coupling::ParticleView& now);
  // body_volume (mean over the last half of the samples), volume_ratio and
  // the table body_edges.
  void report(StageResults& r) const;
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  // The six planes' mean coordinates along their axes: lo x, hi x, lo y, ...
  [[nodiscard]] std::array<double, 6> plane_means(const coupling::ParticleView& now) const;

  MPI_Comm comm_;
  coupling::VolumeProbe probe_;
  double half_plane_ = 0.0;
  std::array<std::vector<std::int64_t>, 6> planes_;  // sorted ids
  std::array<double, 3> start_{};                    // d0 per axis
  std::vector<double> time_, volume_;
  std::array<std::vector<double>, 3> edges_;
};

}  // namespace pbms::dpd
