#include "stages/coupler_stage.hpp"

#include <fmt/format.h>

#include "fit/fit_dpd_potential.hpp"
#include "pbms/config/validator.hpp"
#include "pbms/error.hpp"

namespace pbms::coupler {
namespace {

// The registry of coupler-side kinds, as a driver's StageRegistry.
struct Entry {
  config::StageKindSpec spec;
  std::function<std::unique_ptr<CouplerStageKind>()> create;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> all = {
      {fit::FitDpdPotentialStage::spec(),
       [] { return std::make_unique<fit::FitDpdPotentialStage>(); }},
  };
  return all;
}

}  // namespace

std::filesystem::path CouplerStageContext::stage_dir() const {
  auto d = run_dir_ / stage_.name;
  std::filesystem::create_directories(d);
  return d;
}

YAML::Node CouplerStageContext::driver_params(const std::string& kind,
                                              const YAML::Node& params) const {
  for (const auto& d : drivers_) {
    const config::StageKindSpec* spec = d.stage_kind(kind);
    if (!spec) continue;
    config::Param schema = config::Param::map(
        "stage",
        {config::Param::identifier("name", "").require(), config::Param::string("kind", "")}, "");
    schema.fields.insert(schema.fields.end(), spec->params.begin(), spec->params.end());
    config::Validator v(stage_.name);
    YAML::Node resolved = v.check(schema, params, stage_.name);
    if (!v.errors().empty()) {
      std::vector<std::string> lines;
      for (const auto& e : v.errors()) lines.push_back(e.key_path + ": " + e.message);
      throw Error(fmt::format("stage '{}' built an invalid {} request: {}", stage_.name, kind,
                              fmt::join(lines, "; ")));
    }
    return resolved;
  }
  throw Error(fmt::format("no driver declares stage kind '{}'", kind));
}

config::DriverDescription coupler_description() {
  config::DriverDescription d;
  d.program = config::kCouplerProgram;
  d.short_name = config::kCouplerProgram;
  d.protocol_version = protocol::kProtocolVersion;
  for (const auto& e : entries()) d.stage_kinds.push_back(e.spec);
  return d;
}

std::unique_ptr<CouplerStageKind> create_coupler_stage(const std::string& kind) {
  for (const auto& e : entries()) {
    if (e.spec.kind == kind) return e.create();
  }
  throw Error(fmt::format("the coupler has no stage kind '{}'", kind));
}

}  // namespace pbms::coupler
