// One part's conservation ledger in a concurrent stage: a row per step with
// the part's mass, linear momentum, kinetic energy and its other energies,
// each summed over the part's ranks. Each part keeps its own table. The
// body's momentum needs both tables, so the momentum columns cross between
// the programs once, at the end (momentum_drift), instead of every step.
#pragma once

#include <mpi.h>

#include <array>
#include <string>
#include <vector>

#include "pbms/coupling/concurrent_probes.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::coupling {

class ConservationLedger {
 public:
  struct Row {
    double time = 0.0;                 // ps
    double mass = 0.0;                 // g/mol
    std::array<double, 3> momentum{};  // g/mol Å/ps
    // The momentum the part's walls gave it since the start (g/mol Å/ps):
    // a ledger of `walls` counts it out of the body's momentum.
    std::array<double, 3> wall_impulse{};
    double kinetic = 0.0;          // eV
    std::vector<double> energies;  // eV, in the order of the names
  };

  // `energies`: the names of the part's other energy columns; `walls`: the
  // part has walls, whose impulse the rows carry. Collective use over
  // `comm`, the part's ranks.
  ConservationLedger(MPI_Comm comm, std::vector<std::string> energies, bool walls = false);

  // This rank's mass, momentum and kinetic energy at `time`, with room for
  // the other energies.
  [[nodiscard]] Row motion_of(double time, const ParticleView& now) const;
  // Sums this rank's row over the part's ranks (one allreduce) and keeps it.
  // Throws pbms::Error when the row has not one value per energy name.
  void add(Row mine);

  // The largest change of the body's momentum since the first row, g/mol
  // Å/ps: this part's rows plus the other program's, which calls this at
  // the same time with as many rows, less what walls gave either. Collective
  // over both programs.
  [[nodiscard]] double momentum_drift(MPI_Comm inter) const;

  [[nodiscard]] std::size_t rows() const { return time_.size(); }
  // The rows so far (already summed over the ranks), under `ledger/`, and
  // this rank's `pending` row not yet added, summed over the ranks.
  // Collective when `pending` is given (on every rank).
  void save(CheckpointArchive& a, const Row* pending = nullptr) const;
  // The rows save() wrote; returns the pending row (time NaN when none).
  Row load(const CheckpointArchive& a);
  // Adds the table `<prefix>_ledger`.
  void report(StageResults& r, const std::string& prefix) const;

 private:
  MPI_Comm comm_;
  std::vector<std::string> names_;
  std::vector<double> time_, mass_, kinetic_;
  bool walls_ = false;
  std::array<std::vector<double>, 3> momentum_, wall_impulse_;
  std::vector<std::vector<double>> energies_;  // per name, per row
};

}  // namespace pbms::coupling
