// A DPD engine's owned particles as the shared probes see them
// (coupling::ParticleView), at unwrapped positions.
#pragma once

#include <vector>

#include "engine/dpd_engine.hpp"
#include "pbms/coupling/concurrent_probes.hpp"

namespace pbms::dpd {

struct DpdView {
  std::vector<Vec3> x;
  std::vector<double> mass;
  coupling::ParticleView view(const DpdEngine& e) {
    const DpdParticles& p = e.particles();
    const OrthogonalBox& box = e.domain().box();
    x.resize(e.owned());
    mass.resize(e.owned());
    for (std::size_t i = 0; i < e.owned(); ++i) {
      for (int a = 0; a < 3; ++a) x[i][a] = p.x[i][a] + p.image[i][a] * box.length(a);
      mass[i] = p.mass(i);
    }
    return {e.owned(), p.id, x, p.v, mass, p.group_mask};
  }
};

}  // namespace pbms::dpd
