// What a dpd_run or dpd_equilibrate stage simulates, built from its
// validated parameters: the box, every particle (the same full set on every
// rank), named groups as bits of each particle's group mask, the pair style
// of the stage's material and the integrator settings.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "integrators/dpd_integrator.hpp"
#include "kernels/dpd_particles.hpp"
#include "kernels/orthogonal_box.hpp"
#include "kernels/pair_style.hpp"
#include "stage/dpd_stage_params.hpp"

namespace pbms::dpd {

struct DpdModel {
  OrthogonalBox box;
  DpdParticles particles;
  std::vector<std::string> group_names;  // bit g of group_mask is group_names[g]
  std::unique_ptr<PairStyle> pair;
  DpdIntegratorSettings settings;
  std::uint32_t prescribed_mask = 0;        // rigid and frozen groups
  std::vector<std::uint32_t> rigid_bodies;  // free rigid bodies, one group each
  // Every rigid, frozen or rigid_body group with the velocity it starts at
  // (the DPD/MPM-grid step prescribes them on the grid).
  struct GroupMotion {
    std::uint32_t mask = 0;
    Vec3 velocity{0.0, 0.0, 0.0};
    bool free_body = false;  // rigid_body: pushed by the net force on it
    double ramp_time = 0.0;  // rigid: `velocity` reached over this time (velocity_ramp.hpp)
  };
  std::vector<GroupMotion> group_motions;

  // Throws pbms::Error naming the known groups when `name` is unknown.
  [[nodiscard]] std::uint32_t group_mask(const std::string& name) const;
};

// The rigid groups on a velocity ramp whose velocity changes before step
// `step`, each with that step's velocity (velocity_ramp.hpp).
struct RampedVelocity {
  std::uint32_t mask = 0;
  Vec3 velocity{0.0, 0.0, 0.0};
};
[[nodiscard]] std::vector<RampedVelocity> ramped_velocities(
    const std::vector<DpdModel::GroupMotion>& motions, std::int64_t step, double dt);

// The pair style a dpd_mesoparticle material's resolved `potential` map
// describes (PairStyleRegistry checks the numbers again).
[[nodiscard]] std::unique_ptr<PairStyle> pair_style_from_yaml(const YAML::Node& potential);

// The final state of a stage, kept in the driver process for a later
// stage's `initial: {from_stage: ...}`. Every rank holds the full set.
// Keeps a stage's final state for a later stage's `initial: {from_stage}`;
// with `write` (one rank) also in <run_dir>/<stage>/final_state.h5, where a
// resumed run finds the states of the stages it did not run again.
void keep_final_state(const std::string& stage, DpdParticles all, bool write);
// The run directory of the stage running now: where final states go.
void use_run_directory(const std::filesystem::path& dir);

// The run seed mixed with the stage name (FNV-1a): each stage's noise
// stream differs from every other's of the same run, on every machine.
[[nodiscard]] std::uint64_t stage_seed(std::uint64_t seed, const std::string& stage);

// `seed` keys the initial velocities. Throws pbms::Error for more than 32
// groups, a reused name, an unknown group in `motion`, an empty system, or
// an unknown from_stage.
[[nodiscard]] DpdModel build_dpd_model(const DpdStageParams& params,
                                       const MesoparticleMaterial& material, std::uint64_t seed,
                                       const std::string& stage);

}  // namespace pbms::dpd
