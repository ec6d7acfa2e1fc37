// Third-order Birch-Murnaghan equation of state and its least-squares fit to
// (V, P) points. A pure kernel: plain vectors in, numbers out.
#pragma once

#include <vector>

namespace pbms::analysis {

// P(V) in the units of b0 (bar in PBMS), for volumes in the units of v0.
double birch_murnaghan_pressure(double v, double v0, double b0, double b0_prime);

struct EosFit {
  double v0 = 0.0;            // volume at P = 0
  double b0 = 0.0;            // bulk modulus at P = 0, units of the pressures
  double b0_prime = 0.0;      // dB/dP at P = 0
  double rms_residual = 0.0;  // RMS pressure misfit, units of the pressures
};

// Fits v0, b0 and b0' by Levenberg-Marquardt (Eigen), minimising pressure
// residuals. Needs at least 3 points; throws pbms::Error otherwise or if the
// fit does not converge.
EosFit fit_birch_murnaghan(const std::vector<double>& volumes,
                           const std::vector<double>& pressures);

}  // namespace pbms::analysis
