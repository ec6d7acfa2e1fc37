// The Sutton-Chen many-body potential (Sutton and Chen 1990, the seed's
// force field, §2.2) as a LAMMPS setfl table for pair_style eam/alloy:
//   E_i = eps [ 1/2 sum_j (a/r_ij)^n - c sqrt(rho_i) ],  rho_i = sum_j (a/r_ij)^m,
// which is EAM with phi(r) = eps (a/r)^n, density f(r) = (a/r)^m and
// embedding F(rho) = -eps c sqrt(rho). LAMMPS has no Sutton-Chen pair style
// of its own; EAM tables are how it takes one.
//
// Sutton and Chen sum over all neighbours. A table needs a cutoff, and a
// hard one would make the energy jump as neighbours cross it: phi and f are
// both multiplied by S(x) = 1 - 10x^3 + 15x^4 - 6x^5 over the last
// `smoothing` of the cutoff (x from 0 to 1), whose value and first two
// derivatives vanish at the cutoff. Below 1 Å, where no two atoms come,
// the tables hold their 1 Å values.
#pragma once

#include <string>

namespace pbms::md {

struct SuttonChenParameters {
  double epsilon = 0.0;  // eV
  double a = 0.0;        // Å
  double c = 0.0;
  double n = 0.0, m = 0.0;
  double cutoff = 0.0;     // Å
  double smoothing = 0.0;  // Å, the width of the switch below the cutoff

  // Pair energy eps (a/r)^n S(r) and density (a/r)^m S(r).
  [[nodiscard]] double pair(double r) const;
  [[nodiscard]] double density(double r) const;
  [[nodiscard]] double switching(double r) const;
};

struct SetflHeader {
  std::string element;  // "Cu"
  double mass = 0.0;    // g/mol
  double lattice_constant = 0.0;
  std::string lattice;  // "fcc"
  int atomic_number = 0;
};

// The whole file. The density table reaches `rho_max` (choose it above the
// densest state a run reaches: several times the crystal's).
[[nodiscard]] std::string sutton_chen_setfl(const SuttonChenParameters& p, const SetflHeader& h,
                                            double rho_max);

// The density of the perfect crystal at lattice constant `a0`: the largest
// a run starts from, for choosing rho_max.
[[nodiscard]] double crystal_density(const SuttonChenParameters& p, const std::string& lattice,
                                     double a0);

}  // namespace pbms::md
