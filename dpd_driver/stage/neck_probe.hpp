// The neck between two sintering bodies (seed §6.4): the smallest diameter
// of the bodies' cross-section perpendicular to the line through their
// centres of mass, between the two centres. The cross-section is counted in
// slabs one plane spacing (a/2) thick along that line; a slab's area is its
// particles' volume (a³/4 each) over its thickness, and its diameter that
// of the circle of the same area. The neck is the narrowest slab in the
// middle half of the line (where the two bodies meet; the bodies' own
// far sides are wider); 0 while some slab there is empty (no contact).
#pragma once

#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

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
  // The table neck_<name> (time, width, centre distance) and the scalars
  // neck_width_<name> (mean over the last `stable_time`), neck_final_<name>
  // and contact_time_<name> (the first sample with a neck; absent if none).
  void report(StageResults& r, double stable_time) const;
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  MPI_Comm comm_;
  coupling::NeckPair spec_;
  std::uint32_t first_, second_;
  double a_;
  std::vector<double> time_, width_, distance_;
};

}  // namespace pbms::dpd
