#include "properties/isotherm.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "kernels/fcc_crystal.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

namespace {

constexpr double kRatioTolerance = 1e-6;
constexpr double kPressureTolerance = 1e-6;  // GPa
// Static points cost microseconds; thermal ones a fraction of a second, and
// from the static root the secant needs two or three.
constexpr int kStaticIterations = 60;
constexpr int kThermalIterations = 12;
// Secant steps are capped at 10 % of V0 (~15 GPa near zero pressure for
// copper), so that one wild slope cannot throw the crystal out of its range.
constexpr double kMaxStep = 0.1;
constexpr double kMinRatio = 0.3;
constexpr double kMaxRatio = 3.0;

bool is_static(const ThermalSettings& thermal) {
  return thermal.temperature == 0.0;
}

ThermalSettings static_of(const ThermalSettings& thermal) {
  ThermalSettings s = thermal;
  s.temperature = 0.0;
  return s;
}

struct Solution {
  IsothermPoint point;
  double slope;  // dP/d(V/V0), GPa, from the last two points
};

// Secant on P(r) = target from r0 (already evaluated) with slope0 for the
// first step. P falls with volume in a stable crystal, so a non-negative
// secant slope (noise, or past the spinodal) is replaced by the last good
// one. A sampled P(V) is smooth only down to a fraction of its error (runs
// of nearby volumes drift apart slowly), so thermal iterations stop once
// the residual is a quarter of the error: closer only chases that roughness.
template <class Evaluate>
Solution solve(const Evaluate& evaluate, double target, IsothermPoint point, double slope0,
               int max_iterations) {
  const auto residual = [&](const IsothermPoint& p) { return std::abs(p.pressure - target); };
  const auto converged = [&](const IsothermPoint& p) {
    return residual(p) <=
           std::max(kPressureTolerance * std::max(1.0, std::abs(target)), 0.25 * p.pressure_error);
  };
  double slope = slope0;
  IsothermPoint best = point;
  for (int iteration = 0; iteration < max_iterations && !converged(point); ++iteration) {
    const double r = point.volume_ratio;
    const double f = point.pressure - target;
    const double step = std::clamp(-f / slope, -kMaxStep, kMaxStep);
    const double next_ratio = std::clamp(r + step, kMinRatio, kMaxRatio);
    const IsothermPoint next = evaluate(next_ratio);
    const double secant = (next.pressure - point.pressure) / (next_ratio - r);
    if (std::isfinite(secant) && secant < 0.0) slope = secant;
    if (residual(next) < residual(best)) best = next;
    point = next;
    if (std::abs(next_ratio - r) <= kRatioTolerance * r) break;
  }
  if (converged(point)) return {point, slope};
  // The secant has stalled: accept the best point if it misses the target
  // by no more than the ratio tolerance at a bulk-modulus slope explains, or
  // (sampled) by its noise. A larger miss means P(V) steps over the target,
  // where a neighbour shell crosses the cutoff of a static crystal, or never
  // reaches it, in tension beyond the spinodal.
  if (residual(best) <= 10.0 * std::abs(slope0) * kRatioTolerance ||
      residual(best) <= 2.0 * best.pressure_error) {
    return {best, slope};
  }
  throw StageFailure("DPD isotherm: no state of pressure " + std::to_string(target) +
                     " GPa; the closest, V/V0 = " + std::to_string(best.volume_ratio) +
                     ", has P = " + std::to_string(best.pressure) +
                     " GPa (beyond the spinodal in tension, or P(V) jumps where a neighbour shell "
                     "crosses the cutoff)");
}

}  // namespace

IsothermPoint isotherm_point(PairStyle& pair, const CrystalSpec& reference,
                             const ThermalSettings& thermal, double volume_ratio) {
  check_property_settings(reference, thermal);
  if (!(volume_ratio > 0.0)) throw Error("DPD isotherm: volume ratio must be > 0");
  const double a = reference.lattice_constant * std::cbrt(volume_ratio);
  const double reach = sampling_neighbour_reach(pair, thermal, a);
  const int needed = static_cast<int>(std::ceil(2.0 * reach * (1.0 + 1e-9) / a));
  if (reference.cells > 0 && reference.cells < needed) {
    throw Error("DPD isotherm: " + std::to_string(reference.cells) +
                " cells are too few for a neighbour reach of " + std::to_string(reach) +
                " Å at V/V0 = " + std::to_string(volume_ratio) + "; at least " +
                std::to_string(needed) + " (or 0, automatic)");
  }
  const int cells = std::max(needed, reference.cells);
  const std::vector<analysis::CauchyStress> samples =
      sample_stress(pair, fcc_crystal(cells, cells, cells, a, reference.mass), thermal, a);
  std::vector<double> pressure(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) pressure[k] = analysis::pressure_of(samples[k]);
  const analysis::BlockAverage p = analysis::block_average(pressure, analysis::kStateBlocks);
  if (!std::isfinite(p.mean)) {
    throw StageFailure("DPD isotherm: the pressure at V/V0 = " + std::to_string(volume_ratio) +
                       " is not finite (the crystal came apart)");
  }
  return {volume_ratio, a, p.mean, p.error};
}

IsothermPoint volume_ratio_at_pressure(PairStyle& pair, const CrystalSpec& reference,
                                       const ThermalSettings& thermal, double pressure_gpa) {
  check_property_settings(reference, thermal);
  const ThermalSettings cold = static_of(thermal);
  const auto cold_point = [&](double r) { return isotherm_point(pair, reference, cold, r); };
  // The static slope at the reference, from a small central difference.
  const double h = 1e-4;
  const double cold_slope =
      (cold_point(1.0 + h).pressure - cold_point(1.0 - h).pressure) / (2.0 * h);
  if (!(cold_slope < 0.0)) {
    throw StageFailure("DPD isotherm: the static crystal at the reference lattice constant has " +
                       std::string("dP/dV >= 0 (unstable); start from another lattice constant"));
  }
  const Solution cold_root =
      solve(cold_point, pressure_gpa, cold_point(1.0), cold_slope, kStaticIterations);
  if (is_static(thermal)) return cold_root.point;

  const auto hot_point = [&](double r) { return isotherm_point(pair, reference, thermal, r); };
  const double start = cold_root.point.volume_ratio;
  return solve(hot_point, pressure_gpa, hot_point(start), cold_root.slope, kThermalIterations)
      .point;
}

double zero_pressure_lattice_constant(PairStyle& pair, const CrystalSpec& start,
                                      const ThermalSettings& thermal) {
  return volume_ratio_at_pressure(pair, start, thermal, 0.0).lattice_constant;
}

}  // namespace pbms::dpd
