#include "driver_catalog.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "pbms/config/body_geometry_check.hpp"
#include "pbms/coupling/concurrent_check.hpp"
#include "pbms/error.hpp"
#include "stages/coupler_stage.hpp"

namespace pbms::coupler {
namespace {

// Every kind that places particles in a box also gets the regions' check,
// after its own.
void attach_geometry_check(config::StageKindSpec& k) {
  const bool has_box = std::any_of(k.params.begin(), k.params.end(),
                                   [](const config::Param& p) { return p.name == "box"; });
  if (!has_box) return;
  auto own = std::move(k.check);
  k.check = [own](const config::StageCheck& c) {
    if (own) own(c);
    config::check_body_geometry(c);
  };
}

}  // namespace

std::vector<config::DriverDescription> discover_drivers(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> programs;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const auto name = entry.path().filename().string();
    if (name.size() > 7 && name.ends_with("_driver") && entry.is_regular_file()) {
      programs.push_back(entry.path());
    }
  }
  if (ec) throw Error(fmt::format("cannot list drivers in '{}': {}", dir.string(), ec.message()));
  std::sort(programs.begin(), programs.end());
  std::vector<config::DriverDescription> out;
  for (const auto& p : programs) {
    const std::string cmd = fmt::format("'{}' --describe 2>&1", p.string());
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
    if (!pipe) throw Error(fmt::format("cannot run '{}'", p.string()));
    std::string text;
    char buf[4096];
    size_t n = 0;
    while ((n = fread(buf, 1, sizeof buf, pipe.get())) > 0) text.append(buf, n);
    const int rc = pclose(pipe.release());
    if (rc != 0) {
      throw Error(fmt::format("'{} --describe' failed: {}", p.filename().string(), text));
    }
    out.push_back(config::driver_from_yaml(YAML::Load(text)));
  }
  // Checks that span programs do not travel in --describe; the coupler,
  // which sees every program's side, holds them.
  for (auto& d : out) {
    for (auto& k : d.stage_kinds) {
      if (!k.partners.empty() && k.kind == "concurrent") k.check = coupling::check_concurrent_stage;
      attach_geometry_check(k);
    }
  }
  if (out.empty()) throw Error(fmt::format("no drivers found in '{}'", dir.string()));
  out.push_back(coupler_description());
  return out;
}

}  // namespace pbms::coupler
