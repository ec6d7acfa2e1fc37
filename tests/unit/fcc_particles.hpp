// Particle sets for the probes' unit tests: the fcc sites of a lattice
// constant `a` (origin on a site) that a predicate keeps, over a block of
// cells, as the arrays a coupling::ParticleView reads.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "pbms/coupling/concurrent_probes.hpp"

namespace pbms::test {

struct FccParticles {
  std::vector<std::int64_t> id;
  std::vector<coupling::Vec3> x, v;
  std::vector<double> mass;
  std::vector<std::uint32_t> groups;

  // Cells i in cells[0] (first, last), j in cells[1], k in cells[2]; each
  // kept site gets id first_id + stride * (its index) and the groups
  // `group_of(site)` gives it.
  template <class Keep, class GroupOf>
  FccParticles(double a, const std::array<std::array<int, 2>, 3>& cells, Keep keep,
               GroupOf group_of, std::int64_t first_id = 0, std::int64_t stride = 1) {
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    for (int i = cells[0][0]; i <= cells[0][1]; ++i) {
      for (int j = cells[1][0]; j <= cells[1][1]; ++j) {
        for (int k = cells[2][0]; k <= cells[2][1]; ++k) {
          for (const auto& b : basis) {
            const coupling::Vec3 p{(i + b[0]) * a, (j + b[1]) * a, (k + b[2]) * a};
            if (!keep(p)) continue;
            id.push_back(first_id + stride * static_cast<std::int64_t>(id.size()));
            x.push_back(p);
            v.push_back({0, 0, 0});
            mass.push_back(1.0);
            groups.push_back(group_of(p));
          }
        }
      }
    }
  }
  [[nodiscard]] coupling::ParticleView view() const { return {x.size(), id, x, v, mass, groups}; }
};

}  // namespace pbms::test
