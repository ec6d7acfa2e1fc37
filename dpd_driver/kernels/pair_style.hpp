// The conservative-force interface of the DPD engine. A style is called once
// per step for the whole neighbour list, never once per pair: each style runs
// its own loop with its pair formula inlined (pair_force_loop.hpp).
#pragma once

#include <array>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "kernels/dpd_particles.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "pbms/config/param.hpp"

namespace pbms::dpd {

// A style's parameters as a user writes them, inline in a workflow or in a
// potential file: numbers in metal units, and names of files (tables).
struct PairStyleParameters {
  std::map<std::string, double, std::less<>> numbers;
  std::map<std::string, std::string, std::less<>> texts;
};

// Whether a call must also sum energy, or energy and virial. Forces alone
// are what most steps need; the energy alone is what a ledger kept every
// step needs, and costs less than the virial's six sums per pair.
enum class Tally { kForcesOnly, kEnergy, kEnergyAndVirial };

struct PairResult {
  double energy = 0.0;  // eV; zero unless tallied
  // The part of energy from pairs with another program's points (the
  // list's partners), eV. Such a pair is evaluated on one rank only and
  // tallied there in full.
  double partner_energy = 0.0;
  // Σ over pairs of r_ij ⊗ f_ij, with r_ij = x_i − x_j and f_ij the force on
  // i from j, in eV; xx, yy, zz, xy, xz, yz as LAMMPS orders them. Pressure is
  // (2 E_kin + trace) / (3 V). Zero unless tallied with kEnergyAndVirial.
  std::array<double, 6> virial{};
};

struct PairFrictionTerm;

class PairStyle {
 public:
  virtual ~PairStyle() = default;

  // Adds the conservative forces to particles.f (the caller clears f, so
  // that dissipative and random forces can be summed into the same array),
  // and with a friction term the DPD pair forces too, in the same pass; its
  // cutoff must not exceed this style's. The list must have been built with
  // at least this style's cutoff.
  PairResult compute(DpdParticles& particles, const HalfNeighbourList& list, Tally tally,
                     const PairFrictionTerm* friction = nullptr);
  // Beyond this distance (Å) the style contributes nothing.
  [[nodiscard]] virtual double cutoff() const = 0;
  // The registry name, as a user writes it in a config.
  [[nodiscard]] virtual std::string_view name() const = 0;

  // In a decomposed run, copies a per-particle array (one value per owned
  // particle, then one per ghost) from owners onto their ghosts. A
  // many-body style calls it between its density and force passes; pair
  // styles never do. Unset (serial) means there are no ghosts.
  using GhostForward = std::function<void(std::vector<double>&)>;
  void set_ghost_forward(GhostForward forward) { ghost_forward_ = std::move(forward); }

 protected:
  virtual PairResult compute_forces(DpdParticles& particles, const HalfNeighbourList& list,
                                    Tally tally, const PairFrictionTerm* friction) = 0;

  GhostForward ghost_forward_;
};

// The `cutoff` and `shift` keys most styles share.
[[nodiscard]] config::Param pair_cutoff_param();
[[nodiscard]] config::Param pair_shift_param();

}  // namespace pbms::dpd
