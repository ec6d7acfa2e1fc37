#include "pbms/geometry/particle_groups.hpp"

#include <algorithm>
#include <iterator>
#include <utility>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::geometry {

void ParticleGroups::add(std::string name, Members members) {
  if (name.empty()) throw Error("a particle group needs a name");
  if (contains(name)) throw Error(fmt::format("particle group '{}' is already defined", name));
  std::sort(members.begin(), members.end());
  members.erase(std::unique(members.begin(), members.end()), members.end());
  if (!members.empty() && members.front() < 0) {
    throw Error(
        fmt::format("particle group '{}' has a negative particle index {}", name, members.front()));
  }
  groups_.emplace(std::move(name), std::move(members));
}

void ParticleGroups::add_region_group(std::string name, std::span<const Vec3> positions,
                                      const Region& region) {
  Members members;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (region.contains(positions[i])) members.push_back(static_cast<Index>(i));
  }
  add(std::move(name), std::move(members));
}

void ParticleGroups::add_union(std::string name, std::string_view a, std::string_view b) {
  const Members& ma = members(a);
  const Members& mb = members(b);
  Members out;
  std::set_union(ma.begin(), ma.end(), mb.begin(), mb.end(), std::back_inserter(out));
  add(std::move(name), std::move(out));
}

void ParticleGroups::add_intersection(std::string name, std::string_view a, std::string_view b) {
  const Members& ma = members(a);
  const Members& mb = members(b);
  Members out;
  std::set_intersection(ma.begin(), ma.end(), mb.begin(), mb.end(), std::back_inserter(out));
  add(std::move(name), std::move(out));
}

void ParticleGroups::add_difference(std::string name, std::string_view a, std::string_view b) {
  const Members& ma = members(a);
  const Members& mb = members(b);
  Members out;
  std::set_difference(ma.begin(), ma.end(), mb.begin(), mb.end(), std::back_inserter(out));
  add(std::move(name), std::move(out));
}

const ParticleGroups::Members& ParticleGroups::members(std::string_view name) const {
  const auto it = groups_.find(name);
  if (it == groups_.end()) {
    std::string known;
    for (const auto& [n, m] : groups_) known += (known.empty() ? "" : ", ") + n;
    throw Error(fmt::format("unknown particle group '{}'; defined groups: {}", name,
                            known.empty() ? "none" : known));
  }
  return it->second;
}

bool ParticleGroups::contains(std::string_view name) const {
  return groups_.find(name) != groups_.end();
}

std::vector<std::string> ParticleGroups::names() const {
  std::vector<std::string> out;
  for (const auto& [name, m] : groups_) out.push_back(name);
  return out;
}

}  // namespace pbms::geometry
