#include "properties/surface_energy.hpp"

#include <cmath>
#include <string>

#include "kernels/fcc_crystal.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

namespace {

double static_energy(PairStyle& pair, FccCrystal& crystal) {
  HalfNeighbourList list(pair.cutoff(), 0.0);
  list.build(crystal.particles, crystal.box);
  crystal.particles.zero_forces();
  return pair.compute(crystal.particles, list, Tally::kEnergy).energy;
}

}  // namespace

SurfaceEnergy surface_energy_100(PairStyle& pair, double lattice_constant, int planes) {
  if (!(lattice_constant > 0.0)) {
    throw Error("surface energy: the lattice constant must be > 0 (got " +
                std::to_string(lattice_constant) + ")");
  }
  if (planes < 2 || planes % 2 != 0) {
    throw Error("surface energy: the slab needs an even number of (100) planes, at least 2 (got " +
                std::to_string(planes) + ")");
  }
  SurfaceEnergy s;
  s.planes = planes;
  s.cells_across =
      static_cast<int>(std::ceil(2.0 * pair.cutoff() * (1.0 + 1e-9) / lattice_constant));
  const int across = s.cells_across;
  constexpr double kMass = 1.0;  // static: the mass does not enter

  FccCrystal bulk = fcc_crystal(across, across, across, lattice_constant, kMass);
  s.bulk_site_energy = static_energy(pair, bulk) / static_cast<double>(bulk.particles.size());

  // Two (100) planes per cell along z; the vacuum beyond each face is wider
  // than the cutoff, so the faces do not see each other.
  FccCrystal slab = fcc_crystal(across, across, planes / 2, lattice_constant, kMass);
  slab.box.periodic[2] = false;
  slab.box.lo[2] -= 2.0 * pair.cutoff();
  slab.box.hi[2] += 2.0 * pair.cutoff();
  const double excess =
      static_energy(pair, slab) - static_cast<double>(slab.particles.size()) * s.bulk_site_energy;
  const double area = slab.box.length(0) * slab.box.length(1);
  s.energy_per_area = excess / (2.0 * area);
  return s;
}

}  // namespace pbms::dpd
