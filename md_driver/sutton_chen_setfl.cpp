#include "sutton_chen_setfl.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace pbms::md {
namespace {

constexpr int kPoints = 10000;   // rows of each table
constexpr double kInnerR = 1.0;  // Å: the tables are flat below

// Five values a line, as LAMMPS' own setfl files are written.
void append_table(std::string& out, int count, const auto& value) {
  for (int k = 0; k < count; ++k) {
    out += fmt::format("{:.16e}{}", value(k), (k % 5 == 4 || k + 1 == count) ? "\n" : " ");
  }
}

}  // namespace

double SuttonChenParameters::switching(double r) const {
  if (r >= cutoff) return 0.0;
  const double start = cutoff - smoothing;
  if (r <= start || !(smoothing > 0.0)) return 1.0;
  const double x = (r - start) / smoothing;
  return 1.0 - x * x * x * (10.0 - 15.0 * x + 6.0 * x * x);
}

double SuttonChenParameters::pair(double r) const {
  return epsilon * std::pow(a / r, n) * switching(r);
}

double SuttonChenParameters::density(double r) const {
  return std::pow(a / r, m) * switching(r);
}

double crystal_density(const SuttonChenParameters& p, const std::string& lattice, double a0) {
  // Sites of the conventional cell; every lattice vector out to the cutoff.
  const bool fcc = lattice == "fcc";
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  const int sites = fcc ? 4 : 2;
  const double bcc[2][3] = {{0, 0, 0}, {0.5, 0.5, 0.5}};
  const int reach = static_cast<int>(std::ceil(p.cutoff / a0)) + 1;
  double rho = 0.0;
  for (int i = -reach; i <= reach; ++i) {
    for (int j = -reach; j <= reach; ++j) {
      for (int k = -reach; k <= reach; ++k) {
        for (int s = 0; s < sites; ++s) {
          const double* b = fcc ? basis[s] : bcc[s];
          const double x = (i + b[0]) * a0, y = (j + b[1]) * a0, z = (k + b[2]) * a0;
          const double r = std::sqrt(x * x + y * y + z * z);
          if (r > 0.0) rho += p.density(r);
        }
      }
    }
  }
  return rho;
}

std::string sutton_chen_setfl(const SuttonChenParameters& p, const SetflHeader& h, double rho_max) {
  const double dr = p.cutoff / (kPoints - 1), drho = rho_max / (kPoints - 1);
  std::string out;
  out += "Sutton-Chen potential tabulated by PBMS md_driver (pair_style eam/alloy)\n";
  out += fmt::format(
      "epsilon {:.10g} eV, a {:.10g} A, c {:.10g}, n {:.10g}, m {:.10g}; cutoff {:.10g} A\n",
      p.epsilon, p.a, p.c, p.n, p.m, p.cutoff);
  out += fmt::format("switched to zero over the last {:.10g} A; flat below {:.3g} A\n", p.smoothing,
                     kInnerR);
  out += fmt::format("1 {}\n", h.element);
  out += fmt::format("{} {:.16e} {} {:.16e} {:.16e}\n", kPoints, drho, kPoints, dr, p.cutoff);
  out += fmt::format("{} {:.10g} {:.10g} {}\n", h.atomic_number, h.mass, h.lattice_constant,
                     h.lattice);
  append_table(out, kPoints, [&](int k) { return -p.epsilon * p.c * std::sqrt(k * drho); });
  append_table(out, kPoints, [&](int k) { return p.density(std::max(k * dr, kInnerR)); });
  // r phi(r), in eV Å.
  append_table(out, kPoints, [&](int k) {
    const double r = k * dr;
    return r * p.pair(std::max(r, kInnerR));
  });
  return out;
}

}  // namespace pbms::md
