#include "fit/dpd_judge.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include <fmt/format.h>

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

std::optional<double> scalar_in_metal(const StageResults& r, const std::string& key) {
  for (const auto& s : r.scalars) {
    if (s.key == key) return units::to_metal(s.value, s.unit);
  }
  return std::nullopt;
}

}  // namespace

YAML::Node DpdJudge::crystal_params(double temperature) const {
  const JudgeSettings& j = settings_.judge;
  YAML::Node p;
  p["name"] = ctx_.stage().name;
  p["material"] = settings_.material;
  p["temperature"] = temperature;
  p["cells"] = j.cells;
  p["gamma"] = j.gamma;
  p["time_step"] = j.time_step;
  p["equilibration_steps"] = j.equilibration_steps;
  p["sampling_steps"] = j.sampling_steps;
  return p;
}

protocol::RunStage DpdJudge::request(const std::string& kind, YAML::Node params,
                                     const YAML::Node& potential) const {
  params["kind"] = kind;
  YAML::Node materials(YAML::NodeType::Map);
  materials[settings_.material] = YAML::Clone(ctx_.materials()[settings_.material]);
  materials[settings_.material]["potential"] = potential;
  protocol::RunStage rs;
  rs.index = -1;
  rs.name = ctx_.stage().name;
  rs.kind = kind;
  rs.params_yaml = yaml_text(ctx_.driver_params(kind, params));
  rs.materials_yaml = yaml_text(materials);
  rs.run_dir = ctx_.run_dir().string();
  rs.seed = ctx_.seed();
  return rs;
}

Judgement DpdJudge::judge(const YAML::Node& potential, double temperature) {
  const auto t0 = std::chrono::steady_clock::now();
  Scheduler& scheduler = ctx_.scheduler();
  // Every state point goes out at once; the scheduler queues what the
  // groups cannot take yet.
  // The elastic request is the longest: it goes first, so that the
  // isotherm shares fill the other groups meanwhile.
  std::optional<protocol::RequestId> elastic;
  if (settings_.elastic) {
    YAML::Node params = crystal_params(temperature);
    params["zero_pressure"] = true;
    elastic = scheduler.submit(kDriver, request("dpd_elastic", params, potential));
  }

  // One request per rank group, each with a contiguous share of the
  // pressures: fewer round trips than a request per pressure, and every
  // pressure is sampled on its own crystal with the same seed, so the shares
  // do not change the answers.
  std::vector<protocol::RequestId> isotherm;
  if (settings_.isotherm) {
    const auto& pressures = settings_.isotherm->pressure;
    const size_t shares = std::min<size_t>(pressures.size(), scheduler.groups(kDriver));
    for (size_t k = 0; k < shares; ++k) {
      YAML::Node params = crystal_params(temperature);
      params["zero_pressure"] = false;
      for (size_t i = k * pressures.size() / shares; i < (k + 1) * pressures.size() / shares; ++i) {
        params["pressures"].push_back(pressures[i]);
      }
      isotherm.push_back(scheduler.submit(kDriver, request("dpd_isotherm", params, potential)));
    }
  }
  std::map<protocol::RequestId, Answer> answers;
  const size_t expected = isotherm.size() + (elastic ? 1 : 0);
  while (answers.size() < expected) {
    auto a = scheduler.next(std::chrono::seconds(1));
    if (!a || std::holds_alternative<protocol::Progress>(*a)) continue;
    answers.emplace(request_of(*a), std::move(*a));
  }

  Judgement j;
  for (const auto& [id, a] : answers) {
    if (const auto* f = std::get_if<protocol::StageFailed>(&a)) {
      j.ok = false;
      if (j.reason.empty()) j.reason = f->reason;
    }
  }
  if (j.ok) {
    for (const auto id : isotherm) {
      const auto& r = std::get<protocol::StageDone>(answers.at(id)).results;
      append_in_metal(r, "volume_per_atom", j.volume_per_atom);
      append_in_metal(r, "pressure_error", j.pressure_error);
    }
    if (elastic) {
      const auto& r = std::get<protocol::StageDone>(answers.at(*elastic)).results;
      j.c11 = scalar_in_metal(r, "c11");
      j.c12 = scalar_in_metal(r, "c12");
      j.c44 = scalar_in_metal(r, "c44");
      j.c11_error = scalar_in_metal(r, "c11_error");
      j.c12_error = scalar_in_metal(r, "c12_error");
      j.c44_error = scalar_in_metal(r, "c44_error");
    }
  }
  j.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return j;
}

}  // namespace pbms::coupler::fit
