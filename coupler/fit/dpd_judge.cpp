#include "fit/dpd_judge.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <map>

#include <fmt/format.h>

#include "pbms/analysis/strain_states.hpp"
#include "pbms/error.hpp"
#include "pbms/io/yaml_file.hpp"
#include "pbms/units.hpp"

namespace pbms::coupler::fit {
namespace {

constexpr const char* kDriver = "dpd_driver";

const Column* find_column(const StageResults& r, const std::string& name) {
  for (const auto& c : r.columns) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

void append_in_metal(const StageResults& r, const std::string& name, std::vector<double>& out) {
  const Column* c = find_column(r, name);
  if (!c) throw Error(fmt::format("the judge's answer has no '{}'", name));
  for (const double v : c->data) out.push_back(units::to_metal(v, c->unit));
}

// A column or scalar as the driver computed it, bit for bit: no unit
// conversion, the unit only checked.
const std::vector<double>& exact_column(const StageResults& r, const std::string& name,
                                        const std::string& unit) {
  const Column* c = find_column(r, name);
  if (!c || c->unit != unit) {
    throw Error(fmt::format("the judge's answer has no '{}' in {}", name, unit));
  }
  return c->data;
}

double exact_scalar(const StageResults& r, const std::string& key, const std::string& unit) {
  for (const auto& s : r.scalars) {
    if (s.key == key && s.unit == unit) return s.value;
  }
  throw Error(fmt::format("the judge's answer has no '{}' in {}", key, unit));
}

// The block means of one strained state's stress (dpd_elastic with a
// strain_state), GPa.
std::vector<analysis::CauchyStress> state_stress(const StageResults& r) {
  static constexpr std::array<const char*, 6> kComponents{"xx", "yy", "zz", "xy", "xz", "yz"};
  std::vector<analysis::CauchyStress> blocks;
  for (size_t k = 0; k < kComponents.size(); ++k) {
    const std::vector<double>& column = exact_column(r, kComponents[k], "GPa");
    blocks.resize(column.size());
    for (size_t b = 0; b < column.size(); ++b) blocks[b][k] = column[b];
  }
  return blocks;
}

}  // namespace

YAML::Node DpdJudge::crystal_params(double temperature) const {
  YAML::Node p;
  p["name"] = ctx_.stage().name;
  p["material"] = settings_.material;
  p["temperature"] = temperature;
  settings_.judge.sampling.write(p);
  return p;
}

protocol::RunStage DpdJudge::request(const std::string& kind, YAML::Node params,
                                     const YAML::Node& potential,
                                     std::optional<double> lattice_constant) const {
  params["kind"] = kind;
  YAML::Node materials(YAML::NodeType::Map);
  materials[settings_.material] = YAML::Clone(ctx_.materials()[settings_.material]);
  materials[settings_.material]["potential"] = potential;
  // yaml-cpp writes a double with max_digits10 digits: the driver reads back
  // the same bits.
  if (lattice_constant) materials[settings_.material]["lattice_constant"] = *lattice_constant;
  protocol::RunStage rs;
  rs.index = -1;
  rs.name = ctx_.stage().name;
  rs.kind = kind;
  rs.params_yaml = yaml_text(ctx_.driver_params(kind, params));
  rs.materials_yaml = yaml_text(materials);
  rs.run_dir = ctx_.run_dir().string();
  rs.seed = settings_.judge.seed.value_or(ctx_.seed());
  return rs;
}

Judgement DpdJudge::judge(const YAML::Node& potential, double temperature) {
  const auto t0 = std::chrono::steady_clock::now();
  Requests pending;
  submit_isotherms(potential, temperature, pending);
  const Answers answers = collect(potential, temperature, pending);
  Judgement j;
  for (const auto& [id, a] : answers) {
    if (const auto* f = std::get_if<protocol::StageFailed>(&a)) {
      j.ok = false;
      if (j.reason.empty()) j.reason = f->reason;
    }
  }
  if (j.ok) j = judgement_of(pending, answers);
  j.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return j;
}

void DpdJudge::submit_isotherms(const YAML::Node& potential, double temperature,
                                Requests& pending) const {
  Scheduler& scheduler = ctx_.scheduler();
  const size_t rows = settings_.isotherm ? settings_.isotherm->pressure.size() : 0;
  // The elastic constants are sampled at the lattice constant of zero
  // pressure, which a dpd_elastic stage solves for first: here a dpd_isotherm
  // request at exactly 0 GPa, the same solve on the same crystal and seed. It
  // goes first, since the strained states wait for it. (The isotherm
  // targets' rows are the pressures their stage reached, never exactly 0, so
  // none of them can stand in for it.)
  if (settings_.elastic) {
    YAML::Node params = crystal_params(temperature);
    params["zero_pressure"] = false;
    params["pressures"].push_back(0.0);
    pending.emplace(scheduler.submit(kDriver, request("dpd_isotherm", params, potential)),
                    Pending{{}, true, std::nullopt});
  }
  // The target pressures. Every pressure is sampled on its own crystal with
  // the same seed, so how they are shared out does not change the answers.
  // Sampled, a pressure takes seconds (a secant over two or three DPD runs)
  // and each is a request of its own: pieces that small let the groups
  // finish together. Static, a pressure takes milliseconds, less than a
  // round trip, and each group gets one contiguous share.
  const size_t shares =
      temperature > 0.0 ? rows : std::min<size_t>(rows, scheduler.groups(kDriver));
  for (size_t k = 0; k < shares; ++k) {
    Pending share;
    YAML::Node params = crystal_params(temperature);
    params["zero_pressure"] = false;
    for (size_t i = k * rows / shares; i < (k + 1) * rows / shares; ++i) {
      share.rows.push_back(i);
      params["pressures"].push_back(settings_.isotherm->pressure[i]);
    }
    pending.emplace(scheduler.submit(kDriver, request("dpd_isotherm", params, potential)),
                    std::move(share));
  }
  // The surface energy is the static crystal's at its own zero pressure,
  // whatever the temperature: milliseconds.
  if (settings_.surface) {
    YAML::Node params;
    params["name"] = ctx_.stage().name;
    params["material"] = settings_.material;
    pending.emplace(scheduler.submit(kDriver, request("dpd_surface_energy", params, potential)),
                    Pending{{}, false, std::nullopt, true});
  }
}

DpdJudge::Answers DpdJudge::collect(const YAML::Node& potential, double temperature,
                                    Requests& pending) const {
  // Every request goes out as soon as it can; the scheduler queues what the
  // groups cannot take yet. The four strained states follow the lattice
  // constant, each a request of its own, so that they spread over the
  // groups; analysis::elastic_constants_from_states combines them as the
  // dpd_elastic stage does.
  Scheduler& scheduler = ctx_.scheduler();
  Answers answers;
  while (answers.size() < pending.size()) {
    auto a = scheduler.next(std::chrono::seconds(1));
    if (!a || std::holds_alternative<protocol::Progress>(*a)) continue;
    const protocol::RequestId id = request_of(*a);
    const auto* done = std::get_if<protocol::StageDone>(&*a);
    if (done && pending.at(id).lattice) {
      const double a0 = exact_column(done->results, "lattice_constant", "Å").at(0);
      for (size_t s = 0; s < analysis::kStrainStates.size(); ++s) {
        YAML::Node params = crystal_params(temperature);
        params["zero_pressure"] = false;
        params["strain_state"] = analysis::strain_state_name(analysis::kStrainStates[s]);
        pending.emplace(scheduler.submit(kDriver, request("dpd_elastic", params, potential, a0)),
                        Pending{{}, false, s});
      }
    }
    answers.emplace(id, std::move(*a));
  }
  return answers;
}

Judgement DpdJudge::judgement_of(const Requests& pending, const Answers& answers) const {
  Judgement j;
  if (settings_.isotherm) {
    const size_t n = settings_.isotherm->pressure.size();
    j.volume_per_atom.assign(n, 0.0);
    j.pressure_error.assign(n, 0.0);
  }
  std::array<std::vector<analysis::CauchyStress>, 4> states;
  std::optional<double> strain;
  for (const auto& [id, p] : pending) {
    const auto& r = std::get<protocol::StageDone>(answers.at(id)).results;
    if (!p.rows.empty()) {
      std::vector<double> volume, error;
      append_in_metal(r, "volume_per_atom", volume);
      append_in_metal(r, "pressure_error", error);
      if (volume.size() != p.rows.size() || error.size() != p.rows.size()) {
        throw Error("the judge's isotherm answer has a row count other than it asked for");
      }
      for (size_t k = 0; k < p.rows.size(); ++k) {
        j.volume_per_atom[p.rows[k]] = volume[k];
        j.pressure_error[p.rows[k]] = error[k];
      }
    }
    if (p.surface) {
      j.surface_energy_100 =
          units::to_metal(exact_scalar(r, "surface_energy_100", "J/m^2"), "J/m^2");
    }
    if (p.state) {
      states[*p.state] = state_stress(r);
      const double e = exact_scalar(r, "strain", "1");
      if (strain && *strain != e) throw Error("the judge's strained states differ in strain");
      strain = e;
    }
  }
  if (settings_.elastic) {
    const analysis::ElasticConstants e = analysis::elastic_constants_from_states(states, *strain);
    j.c11 = units::to_metal(e.c11, "GPa");
    j.c12 = units::to_metal(e.c12, "GPa");
    j.c44 = units::to_metal(e.c44, "GPa");
    j.c11_error = units::to_metal(e.c11_error, "GPa");
    j.c12_error = units::to_metal(e.c12_error, "GPa");
    j.c44_error = units::to_metal(e.c44_error, "GPa");
  }
  return j;
}

}  // namespace pbms::coupler::fit
