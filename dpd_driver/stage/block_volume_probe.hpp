// The volume of a block of DPD particles (the inclusion's cube, seed §6.2.1:
// V is the product of its three edges), measured along the block's own
// axes as it turns (analysis/crystal_block): each particle's lattice site is
// fitted once, at the start, on every rank from the gathered block, and each
// sample takes one reduction of 33 sums. The planes' means take out the
// thermal motion that single outermost particles have.
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "pbms/analysis/crystal_block.hpp"
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
  [[nodiscard]] analysis::BlockEdges measure(const coupling::ParticleView& now) const;

  MPI_Comm comm_;
  coupling::VolumeProbe probe_;
  std::vector<std::int64_t> ids_;  // the block's, sorted; sites_ in the same order
  analysis::BlockSites sites_;
  std::vector<double> time_, volume_, rotation_;
  std::array<std::vector<double>, 3> edges_;
};

}  // namespace pbms::dpd
