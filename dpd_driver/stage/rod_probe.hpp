// The bend of a rod of the DPD part over time (pbms/analysis/rod_bend.hpp):
// the seed's "the rod bends" as a number, the largest lateral deflection of
// its centre line from the chord between its ends. Slabs one lattice
// constant thick along the rod's axis, over the rod's extent at the start.
// A particle stays in the slab it started in: binned by where it is now, an
// end slab gained and lost the particles that necks draw along the axis,
// and its centroid jumped by several ångströms between samples.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/coupling/concurrent_probes.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::dpd {

class RodProbe {
 public:
  // Collective. `mask`: the rod's group; `a`: the lattice constant; `now`:
  // this rank's particles at the start, which fix each particle's slab.
  RodProbe(MPI_Comm comm, coupling::RodBend spec, std::uint32_t mask, double a,
           const coupling::ParticleView& now);

  // Collective over the part's ranks.
  void sample(double t, const coupling::ParticleView& now);
  // The table rod_<name> (time, bend) and the scalars rod_deflection_<name>
  // (the largest bend over the run) and rod_bend_initial_<name>.
  void report(StageResults& r) const;
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  [[nodiscard]] double plane_phase(const coupling::ParticleView& now, double h) const;
  void assign_slabs(const coupling::ParticleView& now);
  [[nodiscard]] std::optional<std::size_t> slab_of(std::int64_t id) const;

  MPI_Comm comm_;
  coupling::RodBend spec_;
  std::uint32_t mask_;
  double a_, lo_ = 0.0;
  std::size_t slabs_ = 0;
  // Every rod particle's id, sorted, and the slab it started in.
  std::vector<std::int64_t> ids_;
  std::vector<std::uint32_t> slab_of_;
  std::vector<double> time_, bend_;
};

}  // namespace pbms::dpd
