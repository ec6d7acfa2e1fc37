// The decomposed DPD/DPDE engine the dpd_driver stages run: particles,
// ghosts, neighbour list, pair style and integrator on one rank of a
// driver, with the MPI kept to the domain, ghost and migration classes.
//
// Pairs that straddle two ranks are evaluated on both ("newton off"), so a
// step needs no reverse communication and each rank's forces are exactly
// those of a serial run up to summation order; the pair noise is keyed by
// global ids and step (pair_noise.hpp), so the trajectory does not depend
// on the decomposition. On one rank there are no ghosts at all: periodic
// images come from the neighbour list's shifts, as in DpdIntegrator.
//
// The Shardlow schemes sweep pairs in sequence, so their result depends on
// the sweep order: they take it from ShardlowPairOrder, which does not
// depend on the decomposition, and between its colours hand the velocities
// (and internal energies) their ghosts got back to the owners.
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/domain_decomposition.hpp"
#include "engine/ghost_exchange.hpp"
#include "integrators/dpd_integrator.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/pair_style.hpp"

namespace pbms::dpd {

// Global (all-rank) thermodynamic state.
struct ThermoState {
  double particles = 0.0;
  double kinetic = 0.0;      // eV
  double potential = 0.0;    // eV (conservative pair energy)
  double internal = 0.0;     // eV, Σ u_i (DPDE)
  double temperature = 0.0;  // K, kinetic, 3N − 3 degrees of freedom
  // Pressure tensor (kinetic + conservative virial) / V, bar; xx yy zz xy xz yz.
  std::array<double, 6> pressure{};
  // Conservative virial Σ r_ij ⊗ f_ij, eV (zero unless with_potential).
  std::array<double, 6> virial{};
  Vec3 momentum{};  // g/mol Å/ps
  [[nodiscard]] double total() const { return kinetic + potential + internal; }
};

class DpdEngine {
 public:
  // Every rank passes the same box, style, settings and the same full set
  // of particles; each keeps the ones its sub-box owns. Builds ghosts and
  // list and computes the initial forces. Throws pbms::Error as
  // DpdIntegrator does, and when the box cannot be split over the ranks.
  DpdEngine(MPI_Comm comm, const OrthogonalBox& box, std::unique_ptr<PairStyle> pair,
            const DpdIntegratorSettings& settings, DpdParticles all);

  // Particles of groups in `mask` keep the velocity they have (rigid
  // flyers, grips, frozen walls): they drift but are never kicked. Their
  // forces are still computed, for the grip reaction. Throws pbms::Error
  // for a Shardlow scheme (its pair updates would move them).
  void set_prescribed_groups(std::uint32_t mask);

  // Each group in `masks` moves as one free rigid body (translation only):
  // its particles share one velocity, changed every half kick by the net
  // force on the group over its mass (a flyer launched at a speed). Adds
  // the groups to the prescribed ones. Throws as set_prescribed_groups.
  void set_rigid_bodies(const std::vector<std::uint32_t>& masks);

  // Sets the velocity of this rank's particles in `mask`, a prescribed
  // group (a grip on a velocity ramp, before each step).
  void set_group_velocity(std::uint32_t mask, const Vec3& v);

  // Points of another program that pair with this engine's particles (the
  // MPM ghosts of a concurrent run's interface treatment): each step's set,
  // as particles of `type`, appended after the ghosts before the neighbour
  // list is built, so that owned particles take pair forces from them
  // (conservative, dissipative and random, keyed by their ids). They are
  // never integrated. While a set is given the list is rebuilt at every
  // update_neighbours, because the set changes from step to step. In a
  // decomposed run each rank passes the partners within reach of its own
  // sub-box, imaged along the axes the ranks split. A many-body style gives
  // each the mean density of the particles it pairs with. Throws
  // pbms::Error for a Shardlow scheme.
  void set_partners(const std::vector<Vec3>& x, const std::vector<Vec3>& v,
                    const std::vector<std::int64_t>& id, int type);
  // The same partners as the last set_partners, in the same order, moved:
  // no new list while every partner has moved less than half the skin
  // since the set (the caller's check). Positions are continuous: a partner
  // crossing a periodic face arrives unwrapped.
  void move_partners(const std::vector<Vec3>& x, const std::vector<Vec3>& v);
  // Whether the list must be rebuilt before the next forces: some owned
  // particle moved more than half the skin since the build. Collective.
  [[nodiscard]] bool list_is_stale();
  // The force each partner took from this rank's particles at the last
  // compute_forces, in the order given: minus the reaction on it.
  [[nodiscard]] std::vector<Vec3> partner_forces() const;

  // One step of the scheme: for velocity Verlet, half_kick, drift,
  // update_neighbours, compute_forces, half_kick (a Shardlow scheme sweeps
  // the pairs first). A coupling scheme that moves the particles through
  // a grid calls the phases it needs itself.
  void step();

  // The phases of step(). Each is collective over the engine's ranks.
  void sweep_pairs();  // Shardlow schemes: the pair updates of the dissipative part
  void half_kick();    // v += dt/2 f/m for free particles; rigid bodies by their net force
  void drift();        // x += dt v for owned particles; the step count moves on
  // Ghosts follow their owners, or when a particle moved more than half
  // the skin: wrap, migrate, new ghosts and neighbour list.
  void update_neighbours();
  // Wrap, migrate, ghosts and list now, however little the particles
  // moved: the grid model's ranks must own exactly their cells' particles.
  void rebuild_neighbours() { rebuild(); }
  // Takes the sub-boxes of `partition`'s cells (the grid model): every
  // particle to its new owner, then ghosts, list and forces anew.
  // Collective; throws as DomainDecomposition's partition constructor.
  void decompose_as(const grid::GridPartition& partition);
  // The step count moves on (it keys the pair noise) for a scheme that
  // moved the particles itself (DpdGridStep).
  void count_step() { ++step_; }
  // Pair forces at the current positions (with the dissipative and random
  // parts for velocity Verlet, from the current velocities).
  PairResult compute_forces(Tally tally = Tally::kForcesOnly);
  // Scales the free particles' velocities towards T over tau (Berendsen).
  // With `about_mean` the free particles' velocities are scaled about their
  // mean, which keeps their momentum (a thermostat inside a coupled run).
  void berendsen(double temperature, double tau, bool about_mean = false);

  // What a checkpoint holds of the engine: each rank's owned particles in
  // the order it stores them, as rows of kStateWidth (id, type, groups, x,
  // image, v, f, internal energy, and the position the neighbour list was
  // built from). A checkpoint keeps them rank after rank, with how many
  // each rank held (State, for restore_state).
  static constexpr std::size_t kStateWidth = 19;
  struct State {
    std::vector<double> rows;    // every rank's, rank after rank
    std::vector<double> counts;  // per rank
  };
  [[nodiscard]] std::vector<double> own_rows() const;
  // Takes `state` (every rank the same) as the particles after `step`. On
  // as many ranks as wrote it, each rank takes back its own particles in
  // their order and builds ghosts and list from the positions the writer
  // built them from, then moves on to the current ones: the run goes on
  // bit for bit as the one that wrote it. On another rank count the
  // particles go to their owners in id order and ghosts and list are built
  // anew: the same to round-off. Forces are the state's, not recomputed.
  void restore_state(const State& state, std::int64_t step);

  // All-rank sums; with_potential costs one extra pair pass. The potential
  // counts each pair with a partner in full.
  [[nodiscard]] ThermoState thermo(bool with_potential);
  // This rank's tallies of the last compute_forces (zero unless it was
  // asked to tally): the energy (and virial) of the positions, and the
  // partners, the forces were computed at.
  [[nodiscard]] const PairResult& last_tally() const { return last_tally_; }

  [[nodiscard]] DpdParticles& particles() { return particles_; }
  [[nodiscard]] const DpdParticles& particles() const { return particles_; }
  // Owned particles are [0, owned()); ghosts follow.
  [[nodiscard]] std::size_t owned() const { return owned_; }
  [[nodiscard]] std::int64_t total_particles() const { return total_; }
  [[nodiscard]] std::int64_t step_count() const { return step_; }
  [[nodiscard]] long rebuilds() const { return list_.build_count(); }
  [[nodiscard]] const DomainDecomposition& domain() const { return domain_; }
  [[nodiscard]] const DpdIntegratorSettings& settings() const { return settings_; }
  [[nodiscard]] const PairStyle& pair() const { return *pair_; }
  [[nodiscard]] MPI_Comm comm() const { return domain_.comm(); }

 private:
  void rebuild();

  DomainDecomposition domain_;
  std::unique_ptr<PairStyle> pair_;
  DpdIntegratorSettings settings_;
  GhostExchange ghosts_;
  HalfNeighbourList list_;
  DpdParticles particles_;
  std::size_t owned_ = 0;
  std::int64_t total_ = 0;
  std::int64_t step_ = 0;
  std::uint32_t prescribed_ = 0;
  std::vector<std::uint32_t> bodies_;  // group mask of each free rigid body
  std::vector<double> body_mass_;      // g/mol
  std::vector<double> body_force_;     // scratch, 3 per body
  std::vector<Vec3> scratch_forces_;
  std::unique_ptr<ShardlowPairOrder> sweep_order_;  // Shardlow schemes only
  std::vector<char> touched_;                       // per colour: particles it updated
  DpdParticles partners_;                           // the partners of this step (x, v, id, type)
  std::size_t partner_begin_ = 0;                   // their index in particles_
  bool with_partners_ = false;
  bool partners_changed_ = false;
  std::vector<Vec3> partner_offset_;  // the list build's wrap of each partner
  PairResult last_tally_;
};

}  // namespace pbms::dpd
