// Time integration of DPD and DPDE mesoparticles (serial).
//
// kVelocityVerlet is velocity Verlet with the dissipative force evaluated
// from the half-step velocity v(t) + ½Δt f(t)/m: this is the modified
// velocity Verlet of Groot & Warren (1997) with λ = ½, and what LAMMPS pair
// dpd does under fix nve. Groot & Warren found λ ≈ 0.65 closer to the bath
// temperature for soft fluid potentials at large Δt; here Δt is set by the
// stiff conservative forces of a solid (0.01 ps against a ~0.3 ps phonon
// period), γ Δt / m is ~1e-4–1e-2, and λ = ½ keeps the scheme a plain VV that
// reduces exactly to the NVE integrator at γ = 0.
//
// kShardlow and kShardlowDpde are the S1 splitting (shardlow_sweep.hpp):
// the pairwise stochastic sweep, then a conservative velocity-Verlet step.
// This is the order of LAMMPS fix shardlow + fix nve.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "kernels/dpd_pair_friction.hpp"
#include "kernels/dpd_particles.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/orthogonal_box.hpp"
#include "kernels/pair_style.hpp"
#include "kernels/shardlow_pair_order.hpp"

namespace pbms::dpd {

enum class DpdScheme {
  kNve,             // conservative forces only (γ = 0)
  kVelocityVerlet,  // isothermal DPD, forces summed into one VV step
  kShardlow,        // isothermal DPD, S1 splitting
  kShardlowDpde,    // energy-conserving DPD, S1 splitting
};

struct DpdIntegratorSettings {
  DpdScheme scheme = DpdScheme::kNve;
  double dt = 0.01;   // ps
  double skin = 1.0;  // Å, neighbour list
  // γ, DPD cutoff and seed of every scheme but kNve; temperature only for
  // the isothermal ones.
  DpdPairFriction friction;
  double heat_capacity = 0.0;   // C_v per mesoparticle, eV/K; kShardlowDpde only
  std::int64_t first_step = 0;  // keys the noise, so that a continued run draws fresh numbers
};

// The neighbour-list cutoff a scheme needs: the conservative style's, and
// the DPD cutoff too unless the scheme is kNve.
[[nodiscard]] double interaction_cutoff(const PairStyle& pair, const DpdIntegratorSettings& s);

// True when the scheme adds the DPD friction in the force loop (velocity
// Verlet), whose neighbour list must then keep the pair ids.
[[nodiscard]] bool friction_in_force_loop(const DpdIntegratorSettings& s);

// Throws pbms::Error for a non-positive dt or, outside kNve, a negative γ,
// a non-positive DPD cutoff, a negative bath temperature or (kShardlowDpde)
// a non-positive C_v. Returns its argument.
const DpdIntegratorSettings& checked_settings(const DpdIntegratorSettings& s);

// The pairwise stochastic sweep that opens a step of the Shardlow schemes
// (shardlow_sweep.hpp), over the pairs `order` was built with, colour by
// colour; after_colour runs after each (a decomposed run passes the
// velocities its ghosts got back to their owners there). Nothing for kNve
// and kVelocityVerlet.
void splitting_sweep(DpdParticles& particles, const ShardlowPairOrder& order,
                     const DpdIntegratorSettings& s, std::int64_t step,
                     const std::function<void(int colour)>& after_colour = {});

[[nodiscard]] inline bool is_shardlow(DpdScheme s) {
  return s == DpdScheme::kShardlow || s == DpdScheme::kShardlowDpde;
}

class DpdIntegrator {
 public:
  // Keeps references to particles, box and pair style, which must outlive the
  // integrator. Builds the neighbour list (reach: the larger of the two
  // cutoffs, plus skin) and computes the forces of the initial state. Throws
  // pbms::Error for a non-positive dt or, outside kNve, a negative γ, a
  // non-positive DPD cutoff, or (kShardlowDpde) a non-positive C_v.
  DpdIntegrator(DpdParticles& particles, const OrthogonalBox& box, PairStyle& pair,
                const DpdIntegratorSettings& settings);

  // Advances one time step. With Tally::kEnergyAndVirial the result holds
  // the potential energy and virial at the end of the step.
  PairResult step(Tally tally = Tally::kForcesOnly);

  // Potential energy and virial of the current positions (eV), without
  // touching the forces the next step uses.
  PairResult potential();

  [[nodiscard]] std::int64_t step_count() const { return step_; }
  [[nodiscard]] const HalfNeighbourList& neighbour_list() const { return list_; }
  [[nodiscard]] const DpdIntegratorSettings& settings() const { return settings_; }

 private:
  PairResult compute_forces(Tally tally);
  void rebuild();
  void half_kick();

  DpdParticles& particles_;
  const OrthogonalBox& box_;
  PairStyle& pair_;
  DpdIntegratorSettings settings_;
  HalfNeighbourList list_;
  std::unique_ptr<ShardlowPairOrder> sweep_order_;  // Shardlow schemes only
  std::int64_t step_;
  std::vector<Vec3> scratch_forces_;
};

}  // namespace pbms::dpd
