#include "fit/fit_dpd_potential.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fstream>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlopt.hpp>

// GCC 12 warns inside its own AVX-512 intrinsics when Eigen vectorises with
// them (GCC bug 105593, fixed in 13), as core/src/analysis/equation_of_state.cpp says.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Core>
#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>
#pragma GCC diagnostic pop

#include "fit/dpd_judge.hpp"
#include "fit/evaluation_journal.hpp"
#include "fit/fit_objective.hpp"
#include "fit/parameter_uncertainty.hpp"
#include "pbms/analysis/cubic_moduli.hpp"
#include "pbms/error.hpp"
#include "pbms/io/yaml_file.hpp"
#include "pbms/units.hpp"

namespace pbms::coupler::fit {
namespace {

constexpr const char* kDriver = "dpd_driver";
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Candidates around the best point that measure the Jacobian (the
// parameters' errors, the directions the targets leave undetermined): a
// step of 1 % of each parameter's bounds either side.
constexpr int kJacobianPhase = 2;
constexpr double kJacobianStep = 1e-2;

struct Evaluation {
  int phase = 0;  // 0: global search, 1: local polish
  double temperature = 0.0;
  std::vector<double> params;
  Judgement judgement;
  Residuals residuals;
  double objective = 0.0;  // what the optimiser saw (the penalty for a failure)
};

// Metal unit of a style parameter, for summary.yaml. Morse's alpha is the one
// parameter whose dimension (1/length) the schema has no word for.
std::string parameter_unit(const config::Param& schema, const std::string& style,
                           const std::string& name) {
  if (style == "morse" && name == "alpha") return "1/Å";
  for (const auto& f : schema.variants.at(style)) {
    if (f.name == name && f.dimension != units::Dimension::kNone) {
      return std::string(units::canonical_symbol(f.dimension));
    }
  }
  return "1";
}

// The pair styles' schema as dpd_driver declares it.
const config::Param& schema_of(const CouplerStageContext& ctx) {
  const config::Param* schema = potential_schema(ctx.drivers());
  if (!schema) throw Error("no driver declares the dpd_mesoparticle material the fit refines");
  return *schema;
}

const char* phase_name(int phase) {
  return phase == 0 ? "global" : phase == 1 ? "local" : "Jacobian";
}

nlopt::algorithm algorithm(const std::string& name) {
  if (name == "crs2_lm") return nlopt::GN_CRS2_LM;
  if (name == "direct_l") return nlopt::GN_DIRECT_L;
  if (name == "bobyqa") return nlopt::LN_BOBYQA;
  if (name == "sbplx") return nlopt::LN_SBPLX;
  throw Error(fmt::format("unknown optimiser '{}'", name));
}

class Fit {
 public:
  Fit(CouplerStageContext& ctx, FitSettings settings)
      : ctx_(ctx),
        s_(std::move(settings)),
        objective_(s_.isotherm, s_.elastic, s_.surface),
        judge_(ctx, s_),
        journal_(ctx.stage_dir() / "evaluations.journal", ctx.resume()),
        potential_schema_(schema_of(ctx)),
        budget_(budget()) {}

  void run() {
    check_cutoff();
    std::vector<double> x(s_.free.size());
    for (size_t k = 0; k < x.size(); ++k) x[k] = to_unit(k, s_.free[k].start);
    nlopt::srand(ctx_.seed());
    const double final_t = s_.judge.temperature;
    if (s_.optimizer.global != "none" && s_.optimizer.global_evaluations > 0) {
      const double t = s_.optimizer.static_prefit ? 0.0 : final_t;
      minimise(algorithm(s_.optimizer.global), 0, t, s_.optimizer.global_evaluations, x);
      x = best_x(t).value_or(x);
    }
    if (s_.optimizer.local != "none" && s_.optimizer.local_evaluations > 0) {
      if (s_.optimizer.local == "levenberg_marquardt") {
        least_squares(final_t, s_.optimizer.local_evaluations, x);
      } else {
        minimise(algorithm(s_.optimizer.local), 1, final_t, s_.optimizer.local_evaluations, x);
      }
    }
    if (!best_x(final_t)) evaluate(x, 1, final_t);  // the answer is judged at T
    if (ctx_.resume()) {
      ctx_.log(fmt::format("resumed: {} evaluations replayed from {}, {} judged now",
                           journal_.replayed(), "evaluations.journal",
                           evaluations_.size() - journal_.replayed()));
    }
    const size_t best = *best_index(final_t);
    const auto jacobian = jacobian_at(best);
    report(best, uncertainties(best, jacobian), degeneracy(best, jacobian));
  }

 private:
  struct Call {
    Fit* fit;
    int phase;
    double temperature;
    std::exception_ptr error;
    nlopt::opt* opt;
  };

  void check_cutoff() const {
    const std::optional<double> cutoff = s_.start_cutoff;
    if (!s_.isotherm || !cutoff) return;
    const auto& v = s_.isotherm->volume_per_atom;
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    check_cutoff_between_shells(*cutoff, *lo, *hi, s_.atoms_per_particle);
  }

  int budget() const {
    int n = 0;
    if (s_.optimizer.global != "none") n += s_.optimizer.global_evaluations;
    if (s_.optimizer.local != "none") n += s_.optimizer.local_evaluations;
    n += 2 * static_cast<int>(s_.free.size());  // the Jacobian at the best point
    return std::max(n, 1);
  }

  // The optimisers search the unit box: each parameter between its bounds,
  // linear or (optimizer.scale: log) in its logarithm.
  double to_unit(size_t k, double v) const {
    const auto& f = s_.free[k];
    if (!(f.upper > f.lower)) return 0.0;
    if (s_.optimizer.log_scale) return std::log(v / f.lower) / std::log(f.upper / f.lower);
    return (v - f.lower) / (f.upper - f.lower);
  }
  double from_unit(size_t k, double u) const {
    const auto& f = s_.free[k];
    if (s_.optimizer.log_scale) return f.lower * std::pow(f.upper / f.lower, u);
    return f.lower + u * (f.upper - f.lower);
  }
  // dv/du at v: how far a unit step of the search moves the parameter.
  double unit_span(size_t k, double v) const {
    const auto& f = s_.free[k];
    return s_.optimizer.log_scale ? v * std::log(f.upper / f.lower) : f.upper - f.lower;
  }

  YAML::Node potential_of(const std::vector<double>& params) const {
    YAML::Node p = YAML::Clone(s_.start_potential);
    for (size_t k = 0; k < params.size(); ++k) p[s_.free[k].name] = params[k];
    return p;
  }

  double evaluate(const std::vector<double>& x, int phase, double temperature) {
    Evaluation e;
    e.phase = phase;
    e.temperature = temperature;
    for (size_t k = 0; k < x.size(); ++k) e.params.push_back(from_unit(k, x[k]));
    if (auto recorded = journal_.replay(phase, temperature, e.params)) {
      if (s_.surface && recorded->ok && !recorded->surface_energy_100) {
        throw Error(
            "evaluations.journal: the recorded candidates have no surface energy, but this fit "
            "has a surface target: this is not the fit that was recorded. Start a new run "
            "instead of --resume");
      }
      e.judgement = *recorded;
    } else {
      e.judgement = judge_.judge(potential_of(e.params), temperature);
      journal_.record({phase, temperature, e.params, e.judgement});
    }
    if (e.judgement.ok) {
      e.residuals = objective_.residuals(e.judgement);
      e.objective = objective_.value(e.residuals);
      penalty_.seen(e.objective);
    } else {
      e.objective = penalty_.value();
    }
    evaluations_.push_back(e);
    show_progress(e);
    return e.objective;
  }

  void show_progress(const Evaluation& e) {
    const auto best = best_index(e.temperature);
    const std::string best_text =
        best ? fmt::format("best {:.4g}", evaluations_[*best].objective) : "no success yet";
    const std::string failed = e.judgement.ok ? "" : " (failed: " + e.judgement.reason + ")";
    ctx_.progress(
        static_cast<int64_t>(evaluations_.size()), budget_,
        fmt::format("{} at {:g} K, {}{}", phase_name(e.phase), e.temperature, best_text, failed));
    if (!e.judgement.ok) {
      ctx_.log(fmt::format("evaluation {} failed, penalty {:.4g}: {}", evaluations_.size(),
                           e.objective, e.judgement.reason));
    }
  }

  static double call(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
    auto* c = static_cast<Call*>(data);
    try {
      return c->fit->evaluate(x, c->phase, c->temperature);
    } catch (...) {
      c->error = std::current_exception();
      c->opt->force_stop();
      return std::numeric_limits<double>::max();
    }
  }

  void minimise(nlopt::algorithm a, int phase, double temperature, int evaluations,
                std::vector<double> x) {
    nlopt::opt opt(a, static_cast<unsigned>(x.size()));
    opt.set_lower_bounds(std::vector<double>(x.size(), 0.0));
    opt.set_upper_bounds(std::vector<double>(x.size(), 1.0));
    opt.set_maxeval(evaluations);
    opt.set_xtol_abs(s_.optimizer.x_tolerance);
    opt.set_ftol_abs(s_.optimizer.f_tolerance);
    Call c{this, phase, temperature, nullptr, &opt};
    opt.set_min_objective(call, &c);
    double value = 0.0;
    try {
      opt.optimize(x, value);
    } catch (const nlopt::roundoff_limited&) {
      // Converged as far as round-off allows: the best point stands.
    } catch (const nlopt::forced_stop&) {
    }
    if (c.error) std::rethrow_exception(c.error);
  }

  // The residuals whose sum of squares is the objective: each fitted
  // residual times the square root of its weight in the objective. A failed
  // candidate spreads its penalty evenly over them.
  std::vector<double> weighted_residuals(const Evaluation& e) const {
    if (!e.judgement.ok) {
      const size_t n = fitted_count();
      return std::vector<double>(n, std::sqrt(e.objective / static_cast<double>(n)));
    }
    std::vector<double> r = fitted_residuals(e.residuals);
    const std::vector<double> scale = objective_.fitted_scales(e.residuals);
    for (size_t i = 0; i < r.size(); ++i) r[i] *= scale[i];
    return r;
  }

  size_t fitted_count() const { return objective_.target_scales().size(); }

  // Levenberg-Marquardt on the weighted residuals, in the unit box of the
  // bounds (a step outside is pulled back onto the box).
  struct LeastSquares {
    using Scalar = double;
    using InputType = Eigen::VectorXd;
    using ValueType = Eigen::VectorXd;
    using JacobianType = Eigen::MatrixXd;
    enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };
    Fit* fit;
    double temperature;
    [[nodiscard]] int inputs() const { return static_cast<int>(fit->s_.free.size()); }
    [[nodiscard]] int values() const { return static_cast<int>(fit->fitted_count()); }
    int operator()(const Eigen::VectorXd& q, Eigen::VectorXd& r) const {
      std::vector<double> x(q.data(), q.data() + q.size());
      for (double& v : x) v = std::clamp(v, 0.0, 1.0);
      if (!fit->repeats_last(x, temperature)) fit->evaluate(x, 1, temperature);
      const auto w = fit->weighted_residuals(fit->evaluations_.back());
      for (size_t i = 0; i < w.size(); ++i) r[static_cast<Eigen::Index>(i)] = w[i];
      return 0;
    }
  };

  // Eigen's forward differences ask again for the point the last step ended
  // at before every Jacobian. The judge gives the same answer for the same
  // candidate and seed, so the last candidate stands in for it rather than
  // judging it twice (one in n + 2 of the polish's candidates).
  [[nodiscard]] bool repeats_last(const std::vector<double>& x, double temperature) const {
    if (evaluations_.empty()) return false;
    const Evaluation& last = evaluations_.back();
    if (last.phase != 1 || last.temperature != temperature) return false;
    for (size_t k = 0; k < x.size(); ++k) {
      if (last.params[k] != from_unit(k, x[k])) return false;
    }
    return true;
  }

  void least_squares(double temperature, int evaluations, const std::vector<double>& start) {
    const std::vector<double> scales = objective_.target_scales();
    if (static_cast<size_t>(std::count_if(scales.begin(), scales.end(),
                                          [](double w) { return w > 0.0; })) < s_.free.size()) {
      throw Error("levenberg_marquardt needs at least as many fitted targets as free parameters");
    }
    LeastSquares f{this, temperature};
    // Forward differences: 1e-6 of a parameter for the static crystal, above
    // the round-off of a judged volume; 1e-3 for a sampled one, whose judged
    // volumes are smooth in the parameters only down to a fraction of their
    // sampling error (the isotherm solve stops there).
    Eigen::NumericalDiff<LeastSquares> diff(f, temperature > 0.0 ? 1e-6 : 1e-12);
    Eigen::LevenbergMarquardt<Eigen::NumericalDiff<LeastSquares>> lm(diff);
    // Eigen counts every call, the n + 1 of each forward-difference Jacobian
    // included, and checks the count after each step: it can pass maxfev by
    // a Jacobian and a step, n + 2 calls, one of which repeats_last saves.
    // So the polish judges at most `evaluations` candidates.
    const int n = static_cast<int>(s_.free.size());
    lm.parameters.maxfev = std::max(1, evaluations - n);
    lm.parameters.xtol = s_.optimizer.x_tolerance;
    lm.parameters.ftol = s_.optimizer.f_tolerance;
    Eigen::VectorXd q =
        Eigen::Map<const Eigen::VectorXd>(start.data(), static_cast<Eigen::Index>(start.size()));
    lm.minimize(q);
  }

  std::optional<size_t> best_index(double temperature) const {
    std::optional<size_t> best;
    for (size_t i = 0; i < evaluations_.size(); ++i) {
      const auto& e = evaluations_[i];
      if (!e.judgement.ok || e.temperature != temperature || e.phase == kJacobianPhase) continue;
      if (!best || e.objective < evaluations_[*best].objective) best = i;
    }
    return best;
  }

  std::optional<std::vector<double>> best_x(double temperature) const {
    const auto i = best_index(temperature);
    if (!i) return std::nullopt;
    std::vector<double> x;
    for (size_t k = 0; k < s_.free.size(); ++k) x.push_back(to_unit(k, evaluations_[*i].params[k]));
    return x;
  }

  // The fitted residuals: trained isotherm rows, the targeted modes, the
  // surface.
  std::vector<double> fitted_residuals(const Residuals& r) const { return objective_.fitted(r); }

  // Their sampling errors at the best point: a pressure error becomes a
  // volume error through the target isotherm's slope dV/dP.
  std::vector<double> residual_errors(const Judgement& j) const {
    std::vector<double> out;
    if (s_.isotherm) {
      const auto& p = s_.isotherm->pressure;
      const auto& v = s_.isotherm->volume_per_atom;
      for (size_t i = 0; i < p.size(); ++i) {
        if (s_.isotherm->held_out[i]) continue;
        const size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, p.size() - 1);
        const double slope = p[b] != p[a] ? (v[b] - v[a]) / (p[b] - p[a]) : 0.0;
        out.push_back(j.pressure_error[i] * std::abs(slope) / v[i]);
      }
    }
    if (s_.elastic) {
      const ElasticTarget& el = *s_.elastic;
      for (const ElasticMode m : elastic_modes(el)) {
        const auto e = mode_error(m, j.c11_error, j.c12_error, j.c44_error);
        out.push_back(e ? *e / *mode_value(m, el.c11, el.c12, el.c44) : 0.0);
      }
    }
    if (s_.surface) out.push_back(0.0);  // static: no sampling error
    return out;
  }

  using Jacobian = std::vector<std::vector<double>>;

  // The Jacobian of the fitted residuals at the best point with respect to
  // the parameters' values, by central differences of 1 % of each
  // parameter's bounds (two candidates per parameter, journalled like any
  // other); none when a candidate fails or the best point sits on a bound.
  // A sampled judge's volumes decorrelate under any change of the
  // parameters, so the step must be large enough for the change to stand
  // above that noise.
  std::optional<Jacobian> jacobian_at(size_t best) {
    const Evaluation centre = evaluations_[best];
    const size_t m = fitted_residuals(centre.residuals).size();
    Jacobian jacobian(m, std::vector<double>(s_.free.size()));
    for (size_t k = 0; k < s_.free.size(); ++k) {
      std::vector<double> x;
      for (size_t j = 0; j < s_.free.size(); ++j) x.push_back(to_unit(j, centre.params[j]));
      // Both sides inside the box: the step shrinks near a bound.
      const double h = std::min({kJacobianStep, x[k], 1.0 - x[k]});
      if (!(h > 0.0)) return std::nullopt;
      std::vector<double> side[2];
      double p[2];
      for (int s = 0; s < 2; ++s) {
        std::vector<double> xs = x;
        xs[k] += s == 0 ? -h : h;
        evaluate(xs, kJacobianPhase, centre.temperature);
        const Evaluation& e = evaluations_.back();
        if (!e.judgement.ok) return std::nullopt;
        side[s] = fitted_residuals(e.residuals);
        p[s] = e.params[k];
      }
      for (size_t i = 0; i < m; ++i) jacobian[i][k] = (side[1][i] - side[0][i]) / (p[1] - p[0]);
    }
    return jacobian;
  }

  // Standard errors of the fitted parameters from the judge's sampling
  // errors; NaN for a static fit, which has no noise.
  std::vector<double> uncertainties(size_t best, const std::optional<Jacobian>& jacobian) const {
    if (!(s_.judge.temperature > 0.0) || !jacobian) {
      return std::vector<double>(s_.free.size(), kNaN);
    }
    // Only the residuals with a sampling error carry it into the
    // parameters: the static surface energy has none.
    const std::vector<double> all = residual_errors(evaluations_[best].judgement);
    Jacobian rows;
    std::vector<double> errors;
    for (size_t i = 0; i < all.size(); ++i) {
      if (!(all[i] > 0.0)) continue;
      rows.push_back((*jacobian)[i]);
      errors.push_back(all[i]);
    }
    if (rows.empty()) return std::vector<double>(s_.free.size(), kNaN);
    return parameter_errors(rows, errors);
  }

  // The Jacobian per step of a parameter's whole bounds, rows weighed as
  // the objective weighs them.
  Degeneracy degeneracy(size_t best, const std::optional<Jacobian>& jacobian) const {
    if (!jacobian) return {};
    const std::vector<double>& at = evaluations_[best].params;
    Jacobian unit = *jacobian;
    for (auto& row : unit) {
      for (size_t k = 0; k < row.size(); ++k) row[k] *= unit_span(k, at[k]);
    }
    Degeneracy d = degeneracy_of(unit, objective_.fitted_scales(evaluations_[best].residuals));
    // The directions as parameter steps per unit step of the search.
    for (auto& v : d.directions) {
      for (size_t k = 0; k < v.size(); ++k) v[k] *= unit_span(k, at[k]);
    }
    return d;
  }

  void report(size_t best, const std::vector<double>& errors, const Degeneracy& degeneracy) {
    const Evaluation& e = evaluations_[best];
    auto& r = ctx_.results();
    const std::string& style = s_.style;
    r.add_scalar("objective", e.objective, "1");
    r.add_scalar("max_residual_trained", objective_.max_trained(e.residuals), "1");
    if (s_.isotherm) {
      r.add_scalar("max_residual_held_out", objective_.max_held_out(e.residuals), "1");
    }
    r.add_scalar("evaluations", static_cast<double>(evaluations_.size()), "1");
    int failed = 0;
    for (const auto& x : evaluations_) failed += x.judgement.ok ? 0 : 1;
    r.add_scalar("failed_evaluations", failed, "1");
    for (size_t k = 0; k < s_.free.size(); ++k) {
      r.add_scalar(s_.free[k].name, e.params[k],
                   parameter_unit(potential_schema_, style, s_.free[k].name), errors[k]);
    }
    write_potential(potential_of(e.params));
    log_table();
    if (s_.isotherm) isotherm_table(e);
    if (s_.elastic) elastic_table(e);
    if (s_.surface && e.judgement.surface_energy_100) {
      r.add_scalar("surface_energy_100",
                   *e.judgement.surface_energy_100 * units::kJoulePerM2PerEvPerA2, "J/m^2");
      r.add_scalar("surface_energy_100_target",
                   s_.surface->energy_100 * units::kJoulePerM2PerEvPerA2, "J/m^2");
    }
    report_degeneracy(degeneracy);
  }

  // The singular values and directions of the weighted Jacobian, in the
  // log, as a table (a direction's parameter steps per singular value) and
  // as the condition number.
  void report_degeneracy(const Degeneracy& d) {
    if (d.singular_values.empty()) return;
    auto& r = ctx_.results();
    r.add_scalar("jacobian_condition_number", d.condition_number(), "1");
    r.add_column("degeneracy", "singular_value", "1", d.singular_values);
    const std::string& style = s_.style;
    for (size_t k = 0; k < s_.free.size(); ++k) {
      std::vector<double> step;
      for (const auto& v : d.directions) step.push_back(v[k]);
      r.add_column("degeneracy", "d_" + s_.free[k].name,
                   parameter_unit(potential_schema_, style, s_.free[k].name), step);
    }
    const auto& weakest = d.directions.back();
    std::string along;
    for (size_t k = 0; k < s_.free.size(); ++k) {
      along += fmt::format(" {} {:+.3g}", s_.free[k].name, weakest[k]);
    }
    ctx_.log(fmt::format(
        "Jacobian singular values {:.3g} (condition number {:.3g}); the weakest direction, per "
        "unit step across the bounds:{}",
        fmt::join(d.singular_values, ", "), d.condition_number(), along));
  }

  void write_potential(const YAML::Node& potential) {
    const std::string text = yaml_text(potential);
    const auto file = ctx_.stage_dir() / "potential.yaml";
    std::ofstream f(file);
    f << fmt::format(
        "# DPD potential fitted by stage '{}' (fit_dpd_potential) to its targets at {:g} K.\n"
        "# The format of configs/potentials/*.yaml: use it as a material's potential_file.\n",
        ctx_.stage().name, s_.judge.temperature);
    f << text << "\n";
    if (!f) throw Error(fmt::format("cannot write {}", file.string()));
    ctx_.results().files.push_back(
        (std::filesystem::path(ctx_.stage().name) / "potential.yaml").string());
    ctx_.results().attributes["potential"] = text;
  }

  void log_table() {
    auto& r = ctx_.results();
    const std::string t = "evaluation_log";
    std::vector<double> index, phase, temp, status, objective, wall;
    for (size_t i = 0; i < evaluations_.size(); ++i) {
      const auto& e = evaluations_[i];
      index.push_back(static_cast<double>(i + 1));
      phase.push_back(e.phase);
      temp.push_back(e.temperature);
      status.push_back(e.judgement.ok ? 1.0 : 0.0);
      objective.push_back(e.objective);
      wall.push_back(e.judgement.wall_s);
      if (!e.judgement.ok)
        r.attributes[fmt::format("evaluation_{}_failure", i + 1)] = e.judgement.reason;
    }
    r.add_column(t, "evaluation", "1", index);
    r.add_column(t, "phase", "1", phase);
    r.add_column(t, "temperature", "K", temp);
    r.add_column(t, "status", "1", status);
    r.add_column(t, "objective", "1", objective);
    r.add_column(t, "wall_s", "s", wall);
    const std::string& style = s_.style;
    for (size_t k = 0; k < s_.free.size(); ++k) {
      std::vector<double> v;
      for (const auto& e : evaluations_) v.push_back(e.params[k]);
      r.add_column(t, s_.free[k].name, parameter_unit(potential_schema_, style, s_.free[k].name),
                   v);
    }
    if (s_.isotherm) {
      for (size_t row = 0; row < s_.isotherm->pressure.size(); ++row) {
        std::vector<double> v;
        for (const auto& e : evaluations_) {
          v.push_back(e.judgement.ok ? e.judgement.volume_per_atom[row] : kNaN);
        }
        r.add_column(t, fmt::format("volume_per_atom_{}", row), "Å^3", v);
      }
    }
    if (s_.elastic) {
      const auto gpa = [](const std::optional<double>& c) {
        return c ? *c / units::kBarPerGPa : kNaN;
      };
      std::vector<double> c11, c12, c44;
      for (const auto& e : evaluations_) {
        c11.push_back(gpa(e.judgement.c11));
        c12.push_back(gpa(e.judgement.c12));
        c44.push_back(gpa(e.judgement.c44));
      }
      r.add_column(t, "c11", "GPa", c11);
      r.add_column(t, "c12", "GPa", c12);
      r.add_column(t, "c44", "GPa", c44);
    }
    if (s_.surface) {
      std::vector<double> gamma;
      for (const auto& e : evaluations_) {
        const auto& g = e.judgement.surface_energy_100;
        gamma.push_back(g ? *g * units::kJoulePerM2PerEvPerA2 : kNaN);
      }
      r.add_column(t, "surface_energy_100", "J/m^2", gamma);
    }
  }

  void isotherm_table(const Evaluation& e) {
    const IsothermTarget& iso = *s_.isotherm;
    std::vector<double> held(iso.held_out.begin(), iso.held_out.end());
    auto& r = ctx_.results();
    r.add_column("isotherm", "pressure", "bar", iso.pressure);
    r.add_column("isotherm", "volume_per_atom_target", "Å^3", iso.volume_per_atom);
    r.add_column("isotherm", "volume_per_atom", "Å^3", e.judgement.volume_per_atom);
    r.add_column("isotherm", "pressure_std_error", "bar", e.judgement.pressure_error);
    r.add_column("isotherm", "residual", "1", e.residuals.isotherm);
    r.add_column("isotherm", "held_out", "1", held);
  }

  void elastic_table(const Evaluation& e) {
    const ElasticTarget& el = *s_.elastic;
    const auto gpa = [](const std::optional<double>& c) {
      return c ? *c / units::kBarPerGPa : kNaN;
    };
    auto& r = ctx_.results();
    r.add_column("elastic", "index", "1", {11, 12, 44});
    r.add_column("elastic", "target", "GPa", {gpa(el.c11), gpa(el.c12), gpa(el.c44)});
    r.add_column("elastic", "fitted", "GPa",
                 {gpa(e.judgement.c11), gpa(e.judgement.c12), gpa(e.judgement.c44)});
    r.add_column(
        "elastic", "fitted_std_error", "GPa",
        {gpa(e.judgement.c11_error), gpa(e.judgement.c12_error), gpa(e.judgement.c44_error)});
    // What tension feels, and the modes the fit weighs.
    const auto& j = e.judgement;
    if (!j.c11 || !j.c12) return;
    const analysis::CubicModuli fitted{*j.c11, *j.c12, j.c44.value_or(0.0)};
    r.add_scalar("bulk_modulus", fitted.bulk_modulus() / units::kBarPerGPa, "GPa");
    r.add_scalar("tetragonal_shear_modulus", fitted.tetragonal_shear_modulus() / units::kBarPerGPa,
                 "GPa");
    r.add_scalar("youngs_modulus_100", fitted.youngs_modulus_100() / units::kBarPerGPa, "GPa");
    if (el.c11 && el.c12) {
      const analysis::CubicModuli target{*el.c11, *el.c12, el.c44.value_or(0.0)};
      r.add_scalar("youngs_modulus_100_target", target.youngs_modulus_100() / units::kBarPerGPa,
                   "GPa");
    }
  }

  CouplerStageContext& ctx_;
  FitSettings s_;
  FitObjective objective_;
  DpdJudge judge_;
  EvaluationJournal journal_;
  FailurePenalty penalty_;
  std::vector<Evaluation> evaluations_;
  const config::Param& potential_schema_;  // the pair styles' keys (their units)
  int budget_;
};

}  // namespace

void FitDpdPotentialStage::run(CouplerStageContext& ctx) {
  FitSettings settings = FitSettings::from_yaml(ctx.params(), ctx.materials());
  Scheduler& scheduler = ctx.scheduler();
  const int whole = scheduler.link(kDriver).app.size;
  scheduler.regroup(kDriver, settings.group_ranks);
  ctx.log(fmt::format("fit on {} group{} of dpd_driver", scheduler.groups(kDriver),
                      scheduler.groups(kDriver) == 1 ? "" : "s"));
  Fit(ctx, std::move(settings)).run();
  scheduler.regroup(kDriver, whole);
}

}  // namespace pbms::coupler::fit
