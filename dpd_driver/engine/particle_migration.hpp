// Hands particles that left this rank's sub-box to the rank that owns them
// now. Called when the neighbour list is rebuilt, so that no particle has
// moved more than about half a skin since the last call: one hop to a face
// neighbour per split axis suffices. Positions come wrapped on the
// periodic axes (the rebuild wraps first, the grid pass wraps as it
// moves), so a particle that crossed a periodic face goes the short way
// round the ring of ranks.
#pragma once

#include "engine/domain_decomposition.hpp"
#include "kernels/dpd_particles.hpp"

namespace pbms::dpd {

// `particles` holds owned particles only (ghosts dropped). Keeps their
// relative order; arrivals are appended.
void migrate_particles(const DomainDecomposition& domain, DpdParticles& particles);

// Hands every particle to its owner however far it is, by one allgather of
// all of them: for a change of decomposition (once per run), not per step.
// `particles` holds owned particles only, wrapped on the periodic axes.
// Keeps the particles in the order of their old ranks and places there.
void redistribute_particles(const DomainDecomposition& domain, DpdParticles& particles);

}  // namespace pbms::dpd
