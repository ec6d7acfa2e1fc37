// The neck between two sintering bodies of the DPD part over time, by the
// rule of pbms/analysis/neck_width.hpp (seed §6.4), summed over the part's
// ranks.
#pragma once

#include <mpi.h>

#include <cstdint>

#include "pbms/analysis/neck_history.hpp"
#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/coupling/concurrent_probes.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::dpd {

class NeckProbe {
 public:
  // `first`, `second`: the two bodies' group masks; `a`: the lattice
  // constant. Collective use over the part's ranks.
  NeckProbe(MPI_Comm comm, coupling::NeckPair spec, std::uint32_t first, std::uint32_t second,
            double a);

  // Collective over the part's ranks.
  void sample(double t, const coupling::ParticleView& now);
  // See analysis::NeckHistory::report.
  void report(StageResults& r, double stable_time) const;
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  // Collective: the closest approach of the two bodies' members.
  [[nodiscard]] double closest(const coupling::ParticleView& now) const;

  MPI_Comm comm_;
  std::uint32_t first_, second_;
  int rod_axis_;
  double a_;
  analysis::NeckHistory history_;
};

}  // namespace pbms::dpd
