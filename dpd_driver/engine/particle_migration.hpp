// Hands particles that left this rank's sub-box to the rank that owns them
// now. Called when the neighbour list is rebuilt, so that no particle has
// moved more than about half a skin since the last call: one hop to a face
// neighbour per split axis suffices. Crossing a periodic face wraps the
// position and counts the crossing in the particle's image.
#pragma once

#include "engine/domain_decomposition.hpp"
#include "kernels/dpd_particles.hpp"

namespace pbms::dpd {

// `particles` holds owned particles only (ghosts dropped). Keeps their
// relative order; arrivals are appended.
void migrate_particles(const DomainDecomposition& domain, DpdParticles& particles);

}  // namespace pbms::dpd
