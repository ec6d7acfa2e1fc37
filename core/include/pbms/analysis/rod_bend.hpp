// How far a rod has bent (seed §6.4: "the rod bends" when spheres sinter to
// it): the largest distance of its centre line from the chord between its
// ends. The centre line is the centroid of each slab of the rod along its
// axis; the chord joins the centroids of the first and last slabs that hold
// at least half the median slab's members (a partial end plane is left
// out). A straight
// rod gives its slabs' scatter (thermal motion, the lattice's own steps),
// a fraction of an ångström for slabs of a few hundred particles.
#pragma once

#include <array>
#include <vector>

namespace pbms::analysis {

// `slabs`: per slab along the axis, {members, Σx, Σy, Σz}; slabs with fewer
// than half the median's members are skipped. 0 for fewer than three such
// slabs.
[[nodiscard]] double rod_bend(const std::vector<std::array<double, 4>>& slabs);

}  // namespace pbms::analysis
