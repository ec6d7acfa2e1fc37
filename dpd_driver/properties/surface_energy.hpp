// The static (100) surface energy of the DPD fcc crystal, in process and
// without I/O, for the dpd_surface_energy stage.
//
// Why it matters: a fit to bulk targets (the isotherm, B, C' and C44) leaves
// the surface energy free, and the fitted mesoparticle models of one chain
// spread from 2.0 to 5.1 J/m^2 (Mishin's EAM copper: 1.345). A thin rod
// feels it: a 20 x 5 x 5 a_cg rod of the 5.1 J/m^2 model reorients under its
// own surface stress where MD's wire of the same size stands
// (docs/hierarchy.md, "The DPD rod against MD's nanowire").
//
// The energy is the unrelaxed one: a slab of `planes` (100) planes,
// periodic across and free along z, against as many sites of the periodic
// bulk at the same lattice constant, over both faces. For Mishin's copper,
// relaxing the surface lowers it by 0.4 % (plain lmp).
#pragma once

#include "kernels/pair_style.hpp"

namespace pbms::dpd {

struct SurfaceEnergy {
  double energy_per_area = 0.0;   // eV/Å^2, per face
  double bulk_site_energy = 0.0;  // eV, per particle of the bulk crystal
  int planes = 0;                 // (100) planes of the slab
  int cells_across = 0;           // conventional cells along x and y
};

// The (100) surface energy of the crystal of this lattice constant (Å).
// The slab's edges across and the bulk's edges hold at least twice the
// style's cutoff, so each site sees every neighbour once. Throws
// pbms::Error for a non-positive lattice constant, or for fewer than 2 or an
// odd number of planes.
SurfaceEnergy surface_energy_100(PairStyle& pair, double lattice_constant, int planes);

}  // namespace pbms::dpd
