#include "pbms/analysis/quasi_static_pull.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pbms/units.hpp"

namespace pbms::analysis {

double lateral_periods(double youngs_modulus_gpa, double density, double width, double window) {
  if (!(youngs_modulus_gpa > 0.0 && density > 0.0 && width > 0.0)) return std::nan("");
  const double modulus = youngs_modulus_gpa * units::kBarPerGPa / units::kBarPerEvPerA3;  // eV/Å^3
  const double speed = std::sqrt(modulus / density / units::kMvv2e);                      // Å/ps
  return window * speed / (2.0 * width);
}

double fit_window_time(const std::vector<double>& strain, const std::vector<double>& time,
                       double fit_strain) {
  double end = 0.0;
  for (std::size_t k = 0; k < strain.size() && k < time.size(); ++k) {
    if (strain[k] <= fit_strain) end = std::max(end, time[k]);
  }
  return end;
}

void check_quasi_static(StageResults& r, double density, double width, double window) {
  const auto e = r.scalar("youngs_modulus");
  if (!e || !std::isfinite(*e)) return;
  if (*e <= 0.0) {
    r.add_warning(fmt::format(
        "youngs_modulus {:.4g} GPa is not positive: the specimen did not resist the pull over "
        "the fit window",
        *e));
    return;
  }
  const double periods = lateral_periods(*e, density, width, window);
  r.attributes["fit_window_lateral_periods"] = fmt::format("{:.3g}", periods);
  if (periods < kQuasiStaticPeriods) {
    r.add_warning(fmt::format(
        "youngs_modulus {:.4g} GPa comes from a pull too fast to be the material's: its fit "
        "window lasted {:.3g} ps, {:.2g} of the time a bar wave takes to cross the {:.4g} Å "
        "wide specimen and come back, so the rod had no time to contract sideways and the fit "
        "measures a stiffer, uniaxial-strain response; pull more slowly or for longer",
        *e, window, periods, width));
  }
}

}  // namespace pbms::analysis
