// DPD mesoparticles in structure-of-arrays form. Positions, velocities and
// forces are each an array of 3-vectors rather than nine separate arrays: the
// pair loop gathers x[j] and scatters f[j] for neighbours in arbitrary order,
// and one 24-byte record touches one cache line where three arrays touch three.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/orthogonal_box.hpp"

namespace pbms::dpd {

struct DpdParticles {
  std::vector<std::int64_t> id;  // global, unique across ranks; keys the pair noise
  std::vector<int> type;         // index into mass_per_type
  std::vector<Vec3> x;           // position, Å
  std::vector<Vec3> v;           // velocity, Å/ps
  std::vector<Vec3> f;           // force, eV/Å
  // Periodic images crossed, so that x + image * L is the unwrapped position
  // (diffusion, tracked displacements) after positions are wrapped into the box.
  std::vector<std::array<int, 3>> image;
  // DPDE: internal energy of the mesoparticle's unresolved degrees of
  // freedom, eV. Unused (left at zero) by isothermal DPD.
  std::vector<double> internal_energy;
  // Bit g set: the particle belongs to group g of the run (a probe's slab,
  // a rigid grip). Travels with the particle between ranks.
  std::vector<std::uint32_t> group_mask;
  std::vector<double> mass_per_type;  // g/mol

  [[nodiscard]] std::size_t size() const { return x.size(); }
  [[nodiscard]] double mass(std::size_t i) const { return mass_per_type[type[i]]; }

  // Appends a particle with zero force, no image crossings, no internal
  // energy and no groups.
  void add(std::int64_t global_id, int particle_type, const Vec3& position,
           const Vec3& velocity = {0.0, 0.0, 0.0}) {
    id.push_back(global_id);
    type.push_back(particle_type);
    x.push_back(position);
    v.push_back(velocity);
    f.push_back({0.0, 0.0, 0.0});
    image.push_back({0, 0, 0});
    internal_energy.push_back(0.0);
    group_mask.push_back(0);
  }

  // Keeps the first n particles.
  void truncate(std::size_t n) {
    id.resize(n);
    type.resize(n);
    x.resize(n);
    v.resize(n);
    f.resize(n);
    image.resize(n);
    internal_energy.resize(n);
    group_mask.resize(n);
  }

  void zero_forces() {
    for (auto& fi : f) fi = {0.0, 0.0, 0.0};
  }
};

}  // namespace pbms::dpd
