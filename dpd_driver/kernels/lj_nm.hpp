// The n–m Lennard-Jones generalisation with the definition of LAMMPS
// pair_style nm/cut:
//   E(r) = E0 / (n − m) [m (r0/r)^n − n (r0/r)^m],  r < rc,
// minimum −E0 at r0, optionally shifted so that E(rc) = 0.
#pragma once

#include <cmath>
#include <cstddef>
#include <memory>
#include <string_view>

#include "kernels/pair_style.hpp"

namespace pbms::dpd {

class LjNm final : public PairStyle {
 public:
  static constexpr std::string_view kStyle = "lj_nm";

  struct Kernel {
    double e0;
    double r0_squared;
    double n;
    double m;
    double cutoff_squared;
    double energy_shift;

    void evaluate(std::size_t /*i*/, std::size_t /*j*/, double r2, double& energy,
                  double& force_over_r) const {
      // (r0/r)^p = exp(p/2 · ln(r0²/r²)): one logarithm for both powers, no sqrt.
      const double half_log = 0.5 * std::log(r0_squared / r2);
      const double rn = std::exp(n * half_log);
      const double rm = std::exp(m * half_log);
      const double scale = e0 / (n - m);
      energy = scale * (m * rn - n * rm) - energy_shift;
      force_over_r = scale * n * m * (rn - rm) / r2;
    }
  };

  // Parameters: e0 (eV, > 0), r0 (Å, > 0), n > m > 0, cutoff (Å, > 0),
  // shift (0 or 1, default 0).
  static std::unique_ptr<PairStyle> create(const PairStyleParameters& params);
  // The keys of a potential map of this style, and what it computes.
  static std::vector<config::Param> params();
  static constexpr std::string_view kDoc =
      "E0 / (n - m) [m (r0/r)^n - n (r0/r)^m], as LAMMPS pair_style nm/cut";

  LjNm(double e0, double r0, double n, double m, double cutoff, bool shift);

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
