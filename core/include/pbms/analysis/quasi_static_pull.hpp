// Whether a tension test was slow enough for its modulus to be the
// material's. A rod's mean axial stress follows its grips' strain as
// sigma = C11 e + C12 (e_yy + e_zz): the modulus is Young's only once the
// rod has contracted sideways, and a wave must cross its width and come
// back for that, 2W/c with c the bar-wave speed. Grips set moving at once
// also ring the rod in that breathing motion. A fit window shorter than one
// such period measures a stiffness near C11 with a small error bar.
// Measured on the DPD template rod (72.3 x 21.7 x 21.7 Å of Morse copper at
// 298 K, fit to 1 % strain, three seeds each; periods at 55 GPa): grips at
// 2 Å/ps (0.1 periods) give 191-205 ± 2 GPa; at 0.5 Å/ps (0.4) 36-64 ± 19;
// at 0.2 and 0.1 Å/ps (1.0, 2.1) -0.5 to 34 ± 25; at 0.05 Å/ps (4.1)
// 49-50 ± 22 and at 0.02 Å/ps (10) 53-54 ± 17 GPa. The rod's length
// matters less: configs/dpd_grid_tension.yaml's 216.9 Å rod gives 90.9 GPa
// over 0.73 and 91.9 GPa over 2.0 bar-wave transits of its length.
#pragma once

#include <string>
#include <vector>

#include "pbms/results.hpp"

namespace pbms::analysis {

inline constexpr double kQuasiStaticPeriods = 1.0;

// Periods 2W/c of a bar wave, speed c = sqrt(E/rho), across the width W
// (Å) and back in `window` (ps); E in GPa, rho in g/mol/Å^3. NaN unless E,
// rho and W are positive.
[[nodiscard]] double lateral_periods(double youngs_modulus_gpa, double density, double width,
                                     double window);

// The time of the last sample whose strain is at most `fit_strain`: how
// long the modulus fit's window lasted. `strain` and `time` pair up.
[[nodiscard]] double fit_window_time(const std::vector<double>& strain,
                                     const std::vector<double>& time, double fit_strain);

// After a tension test has reported youngs_modulus into `r`: records the
// window's periods as the attribute fit_window_lateral_periods, and adds a
// warning when they are fewer than kQuasiStaticPeriods or the modulus is
// not positive. `width` is the rod's widest lateral extent. Does nothing
// when there is no youngs_modulus.
void check_quasi_static(StageResults& r, double density, double width, double window);

}  // namespace pbms::analysis
