// Tabulated pair potential: a file of (r, U, F) rows, r in Å increasing,
// U in eV, F = −dU/dr in eV/Å; '#' starts a comment, blank lines are skipped.
//
// Between rows the energy is the cubic Hermite interpolant of U with slopes
// −F, and the force is its exact derivative. LAMMPS `pair_style table linear`
// interpolates U and F separately instead, so its force is not the gradient
// of its energy between rows: energy drifts and forces cannot match finite
// differences of the energy. The Hermite curve passes through every U and F
// of the file, so a table sampled from an analytic potential reproduces it at
// the rows and converges to it with fourth order in the row spacing.
//
// Rows may be unevenly spaced (interval found by bisection); evenly spaced
// rows are detected and indexed directly. A pair closer than the first row
// is an error, as in LAMMPS; beyond the cutoff (default: the last row) the
// table contributes nothing.
#pragma once

#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "kernels/pair_style.hpp"

namespace pbms::dpd {

struct PairTableRows {
  std::vector<double> r;       // Å, strictly increasing
  std::vector<double> energy;  // eV
  std::vector<double> force;   // eV/Å, −dU/dr
};

// Reads a three-column table file. Throws pbms::Error naming the file and
// line for a malformed row, fewer than two rows or r not increasing.
PairTableRows read_pair_table(const std::string& path);

class PairTable final : public PairStyle {
 public:
  static constexpr std::string_view kStyle = "table";

  struct Kernel {
    const double* r;
    const double* energy;
    const double* slope;  // dU/dr = −F
    std::size_t rows;
    double r_first;
    double inverse_spacing;  // > 0 when rows are evenly spaced, else 0
    double cutoff_squared;

    [[nodiscard]] std::size_t interval(double distance) const;
    void evaluate(std::size_t i, std::size_t j, double r2, double& pair_energy,
                  double& force_over_r) const;
  };

  // Parameters: text `file` (the table), number `cutoff` (Å, optional,
  // default the last r of the table, at most that).
  static std::unique_ptr<PairStyle> create(const PairStyleParameters& params);
  // The keys of a potential map of this style, and what it computes.
  static std::vector<config::Param> params();
  static constexpr std::string_view kDoc = "Tabulated pair potential, cubic Hermite between rows";

  PairTable(PairTableRows rows, double cutoff);

  [[nodiscard]] double cutoff() const override { return cutoff_; }
  [[nodiscard]] std::string_view name() const override { return kStyle; }

  // The interpolated pair energy (eV) and force −dU/dr (eV/Å) at distance r.
  void interpolate(double r, double& energy, double& force) const;

 protected:
  PairResult compute_forces(DpdParticles& particles, const HalfNeighbourList& list, Tally tally,
                            const PairFrictionTerm* friction) override;

 private:
  PairTableRows rows_;
  std::vector<double> slope_;
  Kernel kernel_;
  double cutoff_;
};

}  // namespace pbms::dpd
