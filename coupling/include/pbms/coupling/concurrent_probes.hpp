// What each side of a concurrent stage measures of its own particles, the
// same way on both: the slabs' first motion and the wave speed between
// them, the displacement of the interface's lattice planes, and
// displacement profiles along the wave's axis (the conservation ledger is
// ConservationLedger's). Sums run over the side's own ranks; each side reports under
// its own prefix ("dpd", "mpm").
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::coupling {

// A side's owned particles at one moment.
struct ParticleView {
  std::size_t count = 0;
  const std::vector<std::int64_t>& id;
  const std::vector<Vec3>& x;
  const std::vector<Vec3>& v;
  const std::vector<double>& mass;
  const std::vector<std::uint32_t>& groups;
};

// The force along `axis` that held a grip (the prescribed-velocity entries
// whose groups meet `grip`) in the last step, summed over this part's ranks:
// `reactions[i]` is entry i's reaction on this rank, `masks[i]` its groups.
[[nodiscard]] double grip_force(MPI_Comm comm, const std::vector<Vec3>& reactions,
                                const std::vector<std::uint32_t>& masks, std::uint32_t grip,
                                int axis);

class ConcurrentProbes {
 public:
  // `group_names[g]` names bit g of the groups; `bin` is the profile bin
  // width along the axis, Å. Collective over `comm`.
  ConcurrentProbes(MPI_Comm comm, const ConcurrentParams& params,
                   const std::vector<std::string>& group_names, double bin,
                   const ParticleView& start);

  // Every step: the tracked slabs' displacement along the axis.
  void track(std::int64_t step, const ParticleView& now);
  // Every sample_every steps: a profile when the step is one of
  // profile_every.
  void sample(std::int64_t step, const ParticleView& now);
  // The displacement of a group's centre of mass along the axis since the
  // start, NaN when this side has none of it.
  [[nodiscard]] double displacement(const std::string& group, const ParticleView& now) const;
  // This side's share of the two opening planes (wave.opening: the DPD
  // plane, then the MPM plane): each plane's mass, and its mass-weighted
  // displacement and start along the axis. The two sides' shares add up
  // to the planes whichever solver holds them, so a body run by one solver
  // reports the jump across the same planes.
  using PlaneMoments = std::array<double, 6>;
  [[nodiscard]] PlaneMoments opening_moments(const ParticleView& now) const;
  // How far the planes have moved apart along the axis (negative: nearer),
  // from both sides' shares; NaN while a plane has no particles.
  [[nodiscard]] static double opening(const PlaneMoments& mine, const PlaneMoments& theirs);

  // Adds `<prefix>_` scalars and tables.
  void report(StageResults& r, const std::string& prefix) const;

  // Everything a resumed stage needs to go on measuring as if never
  // stopped: the starts (every rank holds them all) and the series so far,
  // under `probes/`.
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  struct Moments {
    double mass = 0.0, first = 0.0;
  };
  [[nodiscard]] std::uint32_t mask_of(const std::string& group) const;
  [[nodiscard]] double displacement(std::uint32_t mask, const ParticleView& now) const;
  [[nodiscard]] std::array<double, 3> moments(std::uint32_t mask, const ParticleView& now) const;
  [[nodiscard]] double centre(std::uint32_t mask, const ParticleView& now) const;
  void profile(double t, const ParticleView& now);
  [[nodiscard]] std::vector<std::vector<double>> timed_histories(const std::string& prefix) const;

  MPI_Comm comm_;
  const ConcurrentParams& p_;
  std::vector<std::string> group_names_;
  std::unordered_map<std::int64_t, Vec3> start_;
  double lo_ = 0.0, bin_ = 1.0;
  std::size_t bins_ = 0;
  std::vector<std::string> tracked_;  // groups this side has, in speed order
  std::vector<std::vector<double>> tracked_s_;
  std::vector<double> tracked_at_;  // centre of mass along the axis at the start, Å
  std::vector<double> track_t_;
  std::vector<double> profile_t_;
  std::vector<std::vector<double>> profiles_;
};

}  // namespace pbms::coupling
