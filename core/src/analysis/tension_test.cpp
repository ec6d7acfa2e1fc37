#include "pbms/analysis/tension_test.hpp"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"

namespace pbms::analysis {

using config::OutputSpec;
using config::Param;
using units::Dimension;

std::vector<Param> TensionTest::params() {
  const YieldRule d;
  return {
      Param::real("fit_strain", Dimension::kNone,
                  "Largest strain of the linear fit; default the strain at the stress maximum, "
                  "so that the fit covers the elastic part")
          .above(0)
          .referable(),
      Param::real("yield_drop", Dimension::kNone,
                  "A load drop is a fall of the smoothed stress from a peak by more than this "
                  "fraction of the peak (and more than 3 times the samples' noise); the first "
                  "one is the yield point (docs/hierarchy.md)")
          .def(d.drop_fraction)
          .above(0)
          .at_most(1),
      Param::real("yield_smoothing", Dimension::kNone,
                  "Strain window of the centred running mean the yield point is found on")
          .def(d.smoothing)
          .above(0),
      GaugeSection::param(),
  };
}

std::vector<OutputSpec> TensionTest::outputs(const std::string& what) {
  return {
      {"youngs_modulus", OutputSpec::Shape::kScalar, "GPa",
       "Slope of the linear fit of stress to strain up to fit_strain (" + what + ")"},
      {"max_stress", OutputSpec::Shape::kScalar, "GPa", "Largest specimen stress (" + what + ")"},
      {"fit_strain", OutputSpec::Shape::kScalar, "1",
       "Upper end of the strain range fitted (" + what + ")"},
      {"yield_stress", OutputSpec::Shape::kScalar, "GPa",
       "Smoothed stress at the first load drop (" + what + "; absent without a drop)"},
      {"yield_strain", OutputSpec::Shape::kScalar, "1",
       "Strain at the first load drop (" + what + "; absent without a drop)"},
      {"tension_curve", OutputSpec::Shape::kTable, "", "Strain and stress samples (" + what + ")"},
      {"gauge_youngs_modulus", OutputSpec::Shape::kScalar, "GPa",
       "Slope of the gauge's Cauchy stress against its strain, up to fit_stress_fraction of its "
       "largest stress (with `gauge`)"},
      {"gauge_max_stress", OutputSpec::Shape::kScalar, "GPa",
       "Largest smoothed Cauchy stress of the gauge (with `gauge`)"},
      {"gauge_yield_stress", OutputSpec::Shape::kScalar, "GPa",
       "The gauge's smoothed stress at its first load drop, or at the maximum of a curve that "
       "levels off (with `gauge`)"},
      {"gauge_yield_strain", OutputSpec::Shape::kScalar, "1",
       "The gauge's strain at that point (with `gauge`)"},
      {"gauge_curve", OutputSpec::Shape::kTable, "",
       "The gauge's strain and Cauchy stress samples (with `gauge`)"},
  };
}

TensionTest TensionTest::from_yaml(const YAML::Node& t) {
  TensionTest s;
  if (t["fit_strain"]) s.fit_strain = t["fit_strain"].as<double>();
  s.yield.drop_fraction = t["yield_drop"].as<double>();
  s.yield.smoothing = t["yield_smoothing"].as<double>();
  if (t["gauge"]) s.gauge = GaugeSection::from_yaml(t["gauge"]);
  return s;
}

namespace {

// The (strain, value) samples whose strain is at most `end`: the points a
// modulus is fitted to.
std::pair<std::vector<double>, std::vector<double>> samples_up_to(const std::vector<double>& strain,
                                                                  const std::vector<double>& value,
                                                                  double end) {
  std::pair<std::vector<double>, std::vector<double>> xy;
  for (std::size_t k = 0; k < strain.size() && k < value.size(); ++k) {
    if (strain[k] <= end) {
      xy.first.push_back(strain[k]);
      xy.second.push_back(value[k]);
    }
  }
  return xy;
}

}  // namespace

double TensionTest::fit_end(const std::vector<double>& strain,
                            const std::vector<double>& stress) const {
  // The elastic part ends at the stress maximum unless the config bounds it.
  const auto peak =
      static_cast<std::size_t>(std::max_element(stress.begin(), stress.end()) - stress.begin());
  return fit_strain ? *fit_strain : (strain.empty() ? 0.0 : strain[peak]);
}

void TensionTest::report_grips(StageResults& r, const std::vector<double>& strain,
                               const std::vector<double>& stress,
                               const std::vector<double>& grip_stress,
                               const std::string& stage) const {
  const double end = fit_end(strain, stress);
  const auto [fx, fy] = samples_up_to(strain, grip_stress, end);
  if (fx.size() < 3) {
    throw Error(
        fmt::format("stage '{}': fewer than 3 grip samples up to a strain of {:.4g}", stage, end));
  }
  const auto fit = fit_line(fx, fy);
  r.add_scalar("grip_youngs_modulus", fit.slope, "GPa", fit.slope_error);
  r.add_column("tension_curve", "grip_stress", "GPa", grip_stress);
}

void TensionTest::report(StageResults& r, const std::vector<double>& strain,
                         const std::vector<double>& stress, const std::string& stage) const {
  const auto peak =
      static_cast<std::size_t>(std::max_element(stress.begin(), stress.end()) - stress.begin());
  const double end = fit_end(strain, stress);
  const auto [fx, fy] = samples_up_to(strain, stress, end);
  if (fx.size() < 3) {
    throw Error(fmt::format(
        "stage '{}': fewer than 3 samples up to a strain of {:.4g}; run longer or sample more "
        "often",
        stage, end));
  }
  r.add_scalar("fit_strain", end, "1");
  if (!fit_strain && peak + 1 == stress.size()) {
    r.attributes["tension_note"] =
        "the stress was still rising at the end: no yield point, the fit covers the whole run";
  }
  const auto fit = fit_line(fx, fy);
  r.add_scalar("youngs_modulus", fit.slope, "GPa", fit.slope_error);
  r.add_scalar("max_stress", stress[peak], "GPa");
  const YieldPoint y = first_load_drop(strain, stress, yield);
  if (y.found) {
    r.add_scalar("yield_stress", y.stress, "GPa");
    r.add_scalar("yield_strain", y.strain, "1");
  } else {
    r.attributes["yield_note"] = fmt::format(
        "no load drop of more than {:g} of the peak stress (noise {:.3g} GPa): no yield point; "
        "run longer",
        yield.drop_fraction, y.noise);
  }
  r.attributes["stress_noise_GPa"] = fmt::format("{:.4g}", y.noise);
  r.add_column("tension_curve", "strain", "1", strain);
  r.add_column("tension_curve", "stress", "GPa", stress);
}

void TensionTest::report_gauge(StageResults& r, const std::vector<double>& strain,
                               const std::vector<double>& stress, const std::string& stage) const {
  const std::vector<double> smooth = running_mean(strain, stress, yield.smoothing);
  if (smooth.empty()) throw Error(fmt::format("stage '{}': no gauge samples", stage));
  const auto top =
      static_cast<std::size_t>(std::max_element(smooth.begin(), smooth.end()) - smooth.begin());
  const double reach = gauge->fit_stress_fraction * smooth[top];
  std::vector<double> fx, fy;
  for (std::size_t k = 0; k < strain.size(); ++k) {
    fx.push_back(strain[k]);
    fy.push_back(stress[k]);
    if (smooth[k] >= reach) break;
  }
  if (fx.size() < 3) {
    throw Error(
        fmt::format("stage '{}': fewer than 3 gauge samples below {:.4g} GPa; sample more often",
                    stage, reach));
  }
  const auto fit = fit_line(fx, fy);
  r.add_scalar("gauge_youngs_modulus", fit.slope, "GPa", fit.slope_error);
  r.add_scalar("gauge_max_stress", smooth[top], "GPa");
  const YieldPoint y = first_load_drop(strain, stress, yield);
  // A curve has levelled off when, a tenth of its strain range before the
  // end, it was already within a load drop's size of its maximum; it
  // yielded where it first came that close.
  const double near =
      smooth[top] - std::max(yield.drop_fraction * smooth[top], yield.noise_multiple * y.noise);
  const auto onset = static_cast<std::size_t>(
      std::find_if(smooth.begin(), smooth.end(), [&](double v) { return v >= near; }) -
      smooth.begin());
  const bool plateau = strain[onset] < strain.back() - 0.1 * (strain.back() - strain.front());
  if (y.found) {
    r.add_scalar("gauge_yield_stress", y.stress, "GPa");
    r.add_scalar("gauge_yield_strain", y.strain, "1");
  } else if (plateau) {
    r.add_scalar("gauge_yield_stress", smooth[top], "GPa");
    r.add_scalar("gauge_yield_strain", strain[onset], "1");
    r.attributes["gauge_yield_note"] =
        "no load drop: the curve levels off; its largest smoothed stress, from where it first "
        "comes within a drop's size of it";
  } else {
    r.attributes["gauge_yield_note"] = "the gauge stress was still rising at the end: no yield";
  }
  r.add_column("gauge_curve", "strain", "1", strain);
  r.add_column("gauge_curve", "stress", "GPa", stress);
}

}  // namespace pbms::analysis
