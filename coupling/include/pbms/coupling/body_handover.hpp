// The one hand-over at the start of a concurrent stage: the program that
// builds the body (dpd_driver: lattice fill or an earlier stage's final
// state, which only it holds) gives the other program the points its
// regions assign to it, with what both must agree on (group names, the
// interface band, the partners' reach, the list skin). A typed struct on
// the wire (protocol/wire.hpp), root to root over the intercommunicator,
// then a broadcast inside the receiving program; once per stage.
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pbms/grid/regular_grid.hpp"
#include "pbms/protocol/wire.hpp"

namespace pbms::coupling {

// What a handed point stands for: a mesoparticle's site of the body's
// continuum, or a point of the gas around the body, near it or far enough
// away to measure the gas's own pressure (gas.probe_distance).
enum class HandedKind : std::uint32_t { kContinuum = 0, kGas = 1, kGasAway = 2 };

// One point of the body that the taking program advances.
struct HandedPoint {
  std::int64_t id = 0;
  std::array<double, 3> x{}, v{};  // Å, Å/ps
  double mass = 0.0;               // g/mol
  std::uint32_t groups = 0;        // bit g: group BodyHandover::groups[g]
  std::uint32_t kind = static_cast<std::uint32_t>(HandedKind::kContinuum);
  PBMS_FIELDS(id, x, v, mass, groups, kind)

  [[nodiscard]] bool is_gas() const {
    return kind != static_cast<std::uint32_t>(HandedKind::kContinuum);
  }
};

struct BodyHandover {
  std::vector<std::string> groups;
  // The interface band: the nodes both programs may deposit on, global
  // indices, as grid::NodeBox holds them.
  std::array<int, 3> band_lo{}, band_hi{};
  double reach = 0.0;  // Å: partners within it are exchanged (pair cutoff plus skin)
  double skin = 0.0;   // Å: partners are chosen afresh when a side has moved half of it
  std::vector<HandedPoint> points;
  // The stress the body's points start with, bar, Voigt order [xx, yy, zz,
  // yz, xz, xy]: under an initial_strain the DPD crystal's (its perfect
  // lattice's static stress at the strain less that unstrained); else 0.
  std::array<double, 6> initial_stress{};
  PBMS_FIELDS(groups, band_lo, band_hi, reach, skin, points, initial_stress)

  [[nodiscard]] grid::NodeBox band() const { return {band_lo, band_hi}; }
};

// Every rank of the giving program calls it; rank 0's data is sent.
void hand_over(MPI_Comm inter, MPI_Comm local, const BodyHandover& body);
// Every rank of the taking program calls it and gets the same data.
[[nodiscard]] BodyHandover take_over(MPI_Comm inter, MPI_Comm local);

}  // namespace pbms::coupling
