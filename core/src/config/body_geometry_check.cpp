#include "pbms/config/body_geometry_check.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "pbms/config/validator.hpp"
#include "pbms/geometry/region_yaml.hpp"

namespace pbms::config {
namespace {

struct Placed {
  std::string name;
  geometry::RegionPtr region;
  YAML::Node raw;  // where to report
  std::string path;
  bool own = true;  // false: an earlier stage's body, reported there
};

geometry::Box common_box(const geometry::Box& a, const geometry::Box& b) {
  geometry::Box c;
  for (std::size_t k = 0; k < 3; ++k) {
    c.lo[k] = std::max(a.lo[k], b.lo[k]);
    c.hi[k] = std::min(a.hi[k], b.hi[k]);
  }
  return c;
}

// A point both regions hold, searched on a lattice of 24 points an axis over
// their common bounding box (closed regions that touch share a face, which
// the lattice's faces include); none when they share no point.
std::optional<geometry::Vec3> common_point(const geometry::Region& a, const geometry::Region& b) {
  const geometry::Box c = common_box(a.bounds(), b.bounds());
  if (c.empty()) return std::nullopt;
  constexpr int kSteps = 24;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; j <= kSteps; ++j) {
      for (int k = 0; k <= kSteps; ++k) {
        const std::array<int, 3> n{i, j, k};
        geometry::Vec3 x{};
        for (std::size_t d = 0; d < 3; ++d) x[d] = c.lo[d] + (c.hi[d] - c.lo[d]) * n[d] / kSteps;
        if (a.contains(x) && b.contains(x)) return x;
      }
    }
  }
  return std::nullopt;
}

std::vector<Placed> placed(const YAML::Node& list, const YAML::Node& raw, const std::string& path,
                           bool own = true) {
  std::vector<Placed> out;
  for (std::size_t i = 0; list && i < list.size(); ++i) {
    out.push_back({list[i]["name"].Scalar(), geometry::region_from_yaml(list[i]["region"]),
                   raw && raw.IsSequence() && i < raw.size() ? raw[i] : YAML::Node(),
                   fmt::format("{}[{}]", path, i), own});
  }
  return out;
}

// This stage's bodies, or those of the stage its state comes from (followed
// back through `initial.from_stage`); none known for a file's state.
std::vector<Placed> bodies_of(const StageCheck& c) {
  // reset(), never `=`: assigning a YAML::Node overwrites the node it refers
  // to, which here is a stage of the workflow. Read through a const view,
  // whose operator[] adds no key.
  YAML::Node stage;
  stage.reset(c.resolved);
  for (int hops = 0; hops < 64 && stage; ++hops) {
    const YAML::Node& s = stage;
    if (s["bodies"] && s["bodies"].size() > 0) {
      const bool own = hops == 0;
      return placed(s["bodies"], own ? c.raw["bodies"] : YAML::Node(), c.path + ".bodies", own);
    }
    const YAML::Node from = s["initial"] ? s["initial"]["from_stage"] : YAML::Node();
    if (!from || !from.IsScalar()) break;
    stage.reset(stage_named(c.workflow, from.Scalar()));
  }
  return {};
}

std::string corner(const geometry::Vec3& x) {
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", x[0], x[1], x[2]);
}

void check_inside_box(const StageCheck& c, const std::vector<Placed>& bodies) {
  const YAML::Node box = c.resolved["box"];
  const auto lo = box["lo"].as<std::vector<double>>();
  const auto hi = box["hi"].as<std::vector<double>>();
  std::array<bool, 3> periodic{};
  for (const auto& a : box["periodic"])
    periodic[static_cast<std::size_t>(a.Scalar()[0] - 'x')] = true;
  for (const Placed& b : bodies) {
    if (!b.own) continue;
    const geometry::Box r = b.region->bounds();
    for (std::size_t a = 0; a < 3; ++a) {
      if (periodic[a] || (r.lo[a] >= lo[a] && r.hi[a] <= hi[a])) continue;
      c.validator.error(b.raw["region"], b.path + ".region",
                        fmt::format("body '{}' spans {} = {:g} .. {:g} Å, beyond the box's {:g} .. "
                                    "{:g} Å: its particles would start outside the box",
                                    b.name, "xyz"[a], r.lo[a], r.hi[a], lo[a], hi[a]));
    }
  }
}

// Touching bodies (a flyer against its target) share a face only; bodies
// that share a volume would put two particles on one lattice site.
void check_apart(const StageCheck& c, const std::vector<Placed>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (!bodies[i].own) continue;
      const geometry::Box box = common_box(bodies[i].region->bounds(), bodies[j].region->bounds());
      if (box.empty() || box.volume() <= 0.0) continue;
      const auto x = common_point(*bodies[i].region, *bodies[j].region);
      if (!x) continue;
      c.validator.error(bodies[i].raw["region"], bodies[i].path + ".region",
                        fmt::format("body '{}' overlaps body '{}' (both hold {}): a lattice site "
                                    "there would hold two particles",
                                    bodies[i].name, bodies[j].name, corner(*x)));
    }
  }
}

// A group or solver region that meets no body holds no particle: a grip
// that pulls nothing, a probe of nothing, an MPM part of vacuum.
void check_meets_bodies(const StageCheck& c, const std::vector<Placed>& regions,
                        const std::vector<Placed>& bodies, const char* what) {
  std::vector<std::string> names;
  for (const Placed& b : bodies) names.push_back(b.name);
  for (const Placed& r : regions) {
    const bool meets = std::any_of(bodies.begin(), bodies.end(), [&](const Placed& b) {
      return common_point(*r.region, *b.region).has_value();
    });
    if (meets) continue;
    const geometry::Box box = r.region->bounds();
    c.validator.error(
        r.raw["region"], r.path + ".region",
        fmt::format("{} '{}' holds no particle: its region {} .. {} meets no body "
                    "(bodies: {})",
                    what, r.name, corner(box.lo), corner(box.hi), fmt::join(names, ", ")));
  }
}

void check_names_once(const StageCheck& c, const std::vector<Placed>& regions) {
  for (std::size_t i = 0; i < regions.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (regions[i].name != regions[j].name) continue;
      c.validator.error(
          regions[i].raw["name"], regions[i].path + ".name",
          fmt::format("the region name '{}' is already given by regions[{}]", regions[i].name, j));
    }
  }
}

void check_sampling(const StageCheck& c) {
  const YAML::Node steps = c.resolved["steps"], every = c.resolved["sample_every"];
  if (!steps || !every || !steps.IsScalar() || !every.IsScalar()) return;
  if (steps.as<long>() == 0 || every.as<long>() <= steps.as<long>()) return;
  c.validator.error(c.raw["sample_every"] ? c.raw["sample_every"] : c.raw, c.path + ".sample_every",
                    fmt::format("sample_every {} is above steps {}: the run would take no sample, "
                                "and every result read from samples would be missing",
                                every.as<long>(), steps.as<long>()));
}

}  // namespace

void check_body_geometry(const StageCheck& c) {
  check_sampling(c);
  if (!c.resolved["box"]) return;
  const std::vector<Placed> bodies = bodies_of(c);
  check_inside_box(c, bodies);
  check_apart(c, bodies);
  const auto groups = placed(c.resolved["groups"], c.raw["groups"], c.path + ".groups");
  const auto regions = placed(c.resolved["regions"], c.raw["regions"], c.path + ".regions");
  check_names_once(c, regions);
  if (bodies.empty()) return;
  check_meets_bodies(c, groups, bodies, "group");
  check_meets_bodies(c, regions, bodies, "solver region");
}

}  // namespace pbms::config
