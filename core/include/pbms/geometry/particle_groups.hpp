// Named sets of particles (a grip, a gauge section, an impactor) that
// fixes, computes and outputs refer to by name, like LAMMPS groups. Members
// are indices into the engine's particle arrays, kept sorted and unique so
// that set operations are linear merges and output order is reproducible.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pbms/geometry/region.hpp"

namespace pbms::geometry {

class ParticleGroups {
 public:
  using Index = std::int64_t;
  using Members = std::vector<Index>;

  // Sorts and de-duplicates `members`. Throws pbms::Error if the name is
  // empty or already taken (a group is defined once, never silently
  // replaced) or an index is negative.
  void add(std::string name, Members members);
  // Every i with region.contains(positions[i]).
  void add_region_group(std::string name, std::span<const Vec3> positions, const Region& region);
  // Groups from existing groups; throw pbms::Error if `a` or `b` is unknown.
  void add_union(std::string name, std::string_view a, std::string_view b);
  void add_intersection(std::string name, std::string_view a, std::string_view b);
  // Members of `a` that are not in `b`.
  void add_difference(std::string name, std::string_view a, std::string_view b);

  // Sorted, unique. Throws pbms::Error naming the known groups when `name`
  // is unknown.
  [[nodiscard]] const Members& members(std::string_view name) const;
  [[nodiscard]] bool contains(std::string_view name) const;
  // Sorted.
  [[nodiscard]] std::vector<std::string> names() const;
  [[nodiscard]] std::size_t size() const { return groups_.size(); }

 private:
  std::map<std::string, Members, std::less<>> groups_;
};

}  // namespace pbms::geometry
