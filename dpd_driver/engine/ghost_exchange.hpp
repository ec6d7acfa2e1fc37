// Ghost particles of a decomposed DPD run: copies of the particles within
// one interaction reach of this rank's sub-box, at the image position this
// rank sees them. Built axis by axis, down then up (a ghost received along
// x is forwarded along y and z, which fills edges and corners), as LAMMPS'
// brick communication does; then refreshed every step in the same order.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/domain_decomposition.hpp"
#include "kernels/dpd_particles.hpp"

namespace pbms::dpd {

class GhostExchange {
 public:
  GhostExchange(const DomainDecomposition& domain, double reach);

  // Drops old ghosts (everything from `owned` on) and appends fresh ones:
  // id, type, position, velocity and group mask.
  void build(DpdParticles& particles, std::size_t owned);
  // Refreshes ghost positions and velocities from their owners, with the
  // same image shifts as at build().
  void forward(DpdParticles& particles) const;
  // Refreshes a per-particle array on the ghosts (owned values first).
  void forward(std::vector<double>& values) const;
  // The other way: the velocities (and, with internal_energy, the internal
  // energies) of the ghosts marked in `touched` replace their owners' values.
  // At most one copy of a particle may be marked. Marks the copies it sets
  // on the way back (a corner ghost passes through an edge ghost).
  void reverse(DpdParticles& particles, std::vector<char>& touched, bool internal_energy) const;

  [[nodiscard]] std::size_t ghost_count() const { return ghosts_; }

 private:
  struct Swap {
    int axis = 0;
    int send_to = -1, receive_from = -1;  // MPI_PROC_NULL where a free axis ends
    double shift = 0.0;                   // added to the sent coordinate, Å
    std::vector<std::size_t> send;        // indices sent
    std::size_t receive_first = 0, receive_count = 0;
  };
  const DomainDecomposition& domain_;
  double reach_;
  std::vector<Swap> swaps_;
  std::size_t ghosts_ = 0;
  mutable std::vector<double> send_buffer_, receive_buffer_;
};

}  // namespace pbms::dpd
