// The quasicontinuum's ghost-force correction for the momentum-conserving
// interface (Shenoy et al. 1999, as a dead load). An MPM point within the
// cutoff of DPD particles takes their pair forces back, but its
// stress-free continuum holds none of the pair forces its MPM neighbours
// would have exerted: in the body at rest it is pushed or pulled (on
// cu_cg_morse at 0 K the first MPM plane is pushed away from the DPD part
// and the second pulled towards it, about 1.5 eV/Å a point). The
// correction measures the reaction each point takes in the reference state
// and subtracts it from then on, so that the body at rest feels none of
// it and a strained body feels only what the strain changes.
//
// At 0 K the reference state is the first step's (the QC correction
// itself). At a temperature one snapshot holds the particles' thermal
// forces as well; the mean over `average_steps` steps estimates the
// reaction the point takes on average, and during those steps each point
// feels its reaction less the running mean. A stage may instead apply the
// dead loads an earlier stage measured on the same body (write / read).
//
// Each part of the body (a label per point: its MPM region) ends with
// dead loads that sum to zero. A part at rest takes no net force from its
// neighbours on average; what a few picoseconds' mean holds of one is the
// slow relative motion of the parts (6 to 18 eV/Å on the 24 × 6 × 6 a_cg
// rod at 298 K, of either sign with the seed), and subtracting it drove
// the MPM part off by 0.1 to 0.2 Å in 2 ps (docs/concurrent.md). At 0 K
// the sum is zero to round-off and this changes nothing.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <unordered_map>
#include <vector>

#include "pbms/coupling/point_ghosts_across_programs.hpp"
#include "pbms/io/checkpoint_archive.hpp"

namespace pbms::coupling {

class GhostForceCorrection {
 public:
  // `average_steps` ≥ 1: the steps whose mean reaction is the dead load.
  GhostForceCorrection(MPI_Comm comm, std::int64_t average_steps);
  // The dead loads another stage measured and wrote (write()), applied
  // from the first step. Collective over comm; throws pbms::Error when the
  // file cannot be read.
  static GhostForceCorrection read(MPI_Comm comm, const std::filesystem::path& file);

  // One step's reactions on this rank's points (`id[i]` takes `force[i]`;
  // `part[i]` labels the part of the body it belongs to), corrected in
  // place. Collective over comm at the last averaged step, where the ranks
  // pool what they measured of the points that moved between them.
  void correct(std::span<const std::int64_t> id, std::span<const int> part, std::span<Vec3> force);

  [[nodiscard]] bool measured() const { return steps_ >= average_steps_; }
  // The dead loads (every rank holds them all once measured): on how many
  // points, the largest on one point, and the largest net force a part's
  // mean held and balancing removed, eV/Å; none before.
  [[nodiscard]] std::size_t points() const { return dead_.size(); }
  [[nodiscard]] double largest() const;
  [[nodiscard]] double net_removed() const { return net_removed_; }

  // The dead loads for a later stage (read()). Collective over comm.
  void write(const std::filesystem::path& file) const;
  // Everything a resumed stage needs to go on as if never stopped, under
  // `ghost_forces/`. Collective over comm.
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  struct Entry {
    Vec3 force{0.0, 0.0, 0.0};
    int part = 0;
  };
  using ById = std::unordered_map<std::int64_t, Entry>;
  void pool();
  void balance_parts();
  [[nodiscard]] bool rank_zero() const;

  MPI_Comm comm_;
  std::int64_t average_steps_;
  std::int64_t steps_ = 0;
  ById sum_;   // while measuring: this rank's share of each point's summed reactions
  ById dead_;  // once measured: every point's dead load
  double net_removed_ = 0.0;
};

}  // namespace pbms::coupling
