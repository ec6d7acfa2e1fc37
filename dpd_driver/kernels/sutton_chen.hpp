// Sutton–Chen many-body potential (Sutton & Chen 1990):
//   E = ε [ Σ_{i<j} (a/r_ij)^n − c Σ_i ρ_i^p ],   ρ_i = Σ_{j≠i} (a/r_ij)^m,
// every sum over pairs closer than the cutoff; p = 1/2 (the default) is
// Sutton and Chen's square root. The embedding term lets a mesoparticle
// model have C12 ≠ C44, which no pair potential can. The exponent p sets
// the embedding's curvature against its slope: in a cubic crystal the
// curvature reaches only the bulk modulus (a shear at constant volume
// leaves ρ unchanged to first order), so a free p lets a fit move B apart
// from C' and C44, which nickel's constants need (docs/hierarchy.md).
//
// Forces are pairwise central, so the pair loop and its virial apply:
//   −(dE/dr_ij)/r_ij = ε [n (a/r)^n − c m (a/r)^m (g_i + g_j)] / r²,
// with g_i = p ρ_i^(p−1), after a first pass over the list has summed ρ.
// Another program's points paired with the particles (a concurrent run's
// partners) are no list rows, so their sums would be partial: each takes the
// mean g of the particles it pairs with, which share its crystal.
#pragma once

#include <cmath>
#include <cstddef>
#include <memory>
#include <string_view>
#include <vector>

#include "kernels/pair_style.hpp"

namespace pbms::dpd {

class SuttonChen final : public PairStyle {
 public:
  static constexpr std::string_view kStyle = "sutton_chen";

  struct Kernel {
    double epsilon;
    double a_squared;
    double n;
    double m;
    double c;
    double cutoff_squared;
    const double* embedding_slope;  // g_i, one per particle

    void evaluate(std::size_t i, std::size_t j, double r2, double& energy,
                  double& force_over_r) const {
      const double half_log = 0.5 * std::log(a_squared / r2);
      const double rn = std::exp(n * half_log);
      const double rm = std::exp(m * half_log);
      energy = epsilon * rn;  // the embedding energy is summed per particle
      force_over_r =
          epsilon * (n * rn - c * m * rm * (embedding_slope[i] + embedding_slope[j])) / r2;
    }
  };

  // Parameters: epsilon (eV, > 0), a (Å, > 0), n > 0, m > 0, c (> 0),
  // cutoff (Å, > 0), p (optional, 0 < p < 1, default 1/2).
  static std::unique_ptr<PairStyle> create(const PairStyleParameters& params);
  // The keys of a potential map of this style, and what it computes.
  static std::vector<config::Param> params();
  static constexpr std::string_view kDoc =
      "eps [sum (a/r)^n - c sum_i rho_i^p], rho_i = sum_j (a/r_ij)^m, p = 1/2 by default";

  SuttonChen(double epsilon, double a, double n, double m, double c, double cutoff, double p = 0.5);

  [[nodiscard]] double cutoff() const override { return cutoff_; }
  [[nodiscard]] std::string_view name() const override { return kStyle; }

  // ρ_i of the last compute(), one per particle; complete for owned ones.
  [[nodiscard]] const std::vector<double>& density() const { return density_; }

 protected:
  PairResult compute_forces(DpdParticles& particles, const HalfNeighbourList& list, Tally tally,
                            const PairFrictionTerm* friction) override;

 private:
  void give_partners_neighbours_density(const HalfNeighbourList& list,
                                        const DpdParticles& particles);

  // ρ^p and dρ^p/dρ; the square root where p = 1/2, so that Sutton and
  // Chen's own form runs as fast and to the same bits as before p existed.
  [[nodiscard]] double embedding(double rho) const;
  [[nodiscard]] double embedding_slope(double rho, double embedded) const;

  Kernel kernel_;
  double cutoff_;
  double p_;
  std::vector<double> density_;
  std::vector<double> embedding_slope_;
};

}  // namespace pbms::dpd
