// Morse pair potential with the definition of LAMMPS pair_style morse:
//   E(r) = D0 [exp(−2α(r − r0)) − 2 exp(−α(r − r0))],  r < rc,
// optionally shifted by −E(rc) so that E(rc) = 0 (LAMMPS pair_modify shift yes).
#pragma once

#include <cmath>
#include <cstddef>
#include <memory>
#include <string_view>

#include "kernels/branch_free_exp.hpp"
#include "kernels/pair_style.hpp"

namespace pbms::dpd {

class Morse final : public PairStyle {
 public:
  static constexpr std::string_view kStyle = "morse";

  struct Kernel {
    double d0;
    double alpha;
    double r0;
    double cutoff_squared;
    double energy_shift;  // subtracted from every pair energy

    void evaluate(std::size_t /*i*/, std::size_t /*j*/, double r2, double& energy,
                  double& force_over_r) const {
      const double r = std::sqrt(r2);
      // One exponential: exp(−2α dr) is its square.
      const double decay = branch_free_exp(-alpha * (r - r0));
      energy = d0 * decay * (decay - 2.0) - energy_shift;
      force_over_r = 2.0 * alpha * d0 * decay * (decay - 1.0) / r;
    }
  };

  // Parameters: d0 (eV, > 0), alpha (1/Å, > 0), r0 (Å, > 0), cutoff (Å, > 0),
  // shift (0 or 1, default 0).
  static std::unique_ptr<PairStyle> create(const PairStyleParameters& params);
  // The keys of a potential map of this style, and what it computes.
  static std::vector<config::Param> params();
  static constexpr std::string_view kDoc =
      "D0 [exp(-2 alpha (r - r0)) - 2 exp(-alpha (r - r0))], as LAMMPS pair_style morse";

  Morse(double d0, double alpha, double r0, double cutoff, bool shift);

  [[nodiscard]] double cutoff() const override { return cutoff_; }
  [[nodiscard]] std::string_view name() const override { return kStyle; }

 protected:
  PairResult compute_forces(DpdParticles& particles, const HalfNeighbourList& list, Tally tally,
                            const PairFrictionTerm* friction) override;

 private:
  Kernel kernel_;
  double cutoff_;
};

}  // namespace pbms::dpd
