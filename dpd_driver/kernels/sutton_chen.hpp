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
// A knee below the crystal's density (optional): the embedding gains
//   λ ρc^p (k − ρ/ρc)^3   where ρ < k ρc,
// ρc being the density of a site of the perfect fcc crystal of lattice
// constant a (the sum within the cutoff). The term and its first two
// derivatives vanish at the knee k, so the crystal above k ρc keeps Sutton
// and Chen's form, and a site that has lost neighbours (a (100) surface site
// holds about two thirds of ρc) loses less embedding energy. It was built to
// lower a coarse-grained copper's surface energy with C44 kept, and it does,
// but only by taking away the crystal's strength under dilation: with MD's
// tensile states among the fit's targets it gains nothing over the plain
// form (docs/hierarchy.md, "A knee in the embedding"). λ = 0 (the default)
// is the plain form, to the same bits.
//
// Forces are pairwise central, so the pair loop and its virial apply:
//   −(dE/dr_ij)/r_ij = ε [n (a/r)^n − c m (a/r)^m (g_i + g_j)] / r²,
// with g_i = dF/dρ at ρ_i (F the embedding), after a first pass over the
// list has summed ρ.
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
  // cutoff (Å, > 0), p (optional, 0 < p < 1, default 1/2), knee (optional,
  // > 0, default 1) and flattening (optional, >= 0, default 0).
  static std::unique_ptr<PairStyle> create(const PairStyleParameters& params);
  // The keys of a potential map of this style, and what it computes.
  static std::vector<config::Param> params();
  static constexpr std::string_view kDoc =
      "eps [sum (a/r)^n - c sum_i F(rho_i)], rho_i = sum_j (a/r_ij)^m, F = rho^p (p = 1/2 by "
      "default) + flattening rho_c^p (knee - rho/rho_c)^3 below the knee";

  SuttonChen(double epsilon, double a, double n, double m, double c, double cutoff, double p = 0.5,
             double knee = 1.0, double flattening = 0.0);

  [[nodiscard]] double cutoff() const override { return cutoff_; }
  [[nodiscard]] std::string_view name() const override { return kStyle; }

  // ρ_i of the last compute(), one per particle; complete for owned ones.
  [[nodiscard]] const std::vector<double>& density() const { return density_; }

  // ρc: the density of a site of the perfect fcc crystal of lattice constant
  // a, summed within the cutoff; the knee is a fraction of it.
  [[nodiscard]] double crystal_density() const { return crystal_density_; }

 protected:
  PairResult compute_forces(DpdParticles& particles, const HalfNeighbourList& list, Tally tally,
                            const PairFrictionTerm* friction) override;

 private:
  void give_partners_neighbours_density(const HalfNeighbourList& list,
                                        const DpdParticles& particles);

  // ρ^p and dρ^p/dρ; the square root where p = 1/2, so that Sutton and
  // Chen's own form runs as fast and to the same bits as before p existed.
  [[nodiscard]] double power(double rho) const;
  [[nodiscard]] double power_slope(double rho, double powered) const;
  // The knee's term of the embedding and its slope; 0 at and above the knee.
  [[nodiscard]] double knee_term(double rho) const;
  [[nodiscard]] double knee_slope(double rho) const;

  Kernel kernel_;
  double cutoff_;
  double p_;
  double crystal_density_;
  double knee_;
  double knee_scale_;  // λ ρc^p
  std::vector<double> density_;
  std::vector<double> embedding_slope_;
};

}  // namespace pbms::dpd
