// The one loop over a half neighbour list that every conservative style runs,
// with the style's pair formula inlined through a template parameter.
//
// A Kernel provides
//   double cutoff_squared;                                    // Å^2
//   void evaluate(std::size_t i, std::size_t j, double r2,
//                 double& energy, double& force_over_r) const;
// where energy is the pair's contribution (eV) and force_over_r = −(dE/dr)/r
// (eV/Å^2), so that the force on i is force_over_r · r_ij. i and j let a
// many-body style use per-particle quantities; pair styles ignore them.
#pragma once

#include <algorithm>
#include <cstddef>

#include "kernels/dpd_particles.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/pair_style.hpp"

namespace pbms::dpd {

template <Tally kTally, class Kernel>
PairResult pair_force_loop(const Kernel& kernel, DpdParticles& particles,
                           const HalfNeighbourList& list) {
  constexpr bool kTallied = kTally == Tally::kEnergyAndVirial;
  // Each particle's neighbours pass in batches through three loops: gather
  // the pairs inside the cutoff, evaluate the pair formula, scatter forces.
  // The middle loop has no memory dependence between pairs, so a branch-free
  // formula vectorises there; one fused loop would stay scalar.
  constexpr int kBatch = 64;
  alignas(64) double dx[kBatch], dy[kBatch], dz[kBatch], r2[kBatch];
  alignas(64) double pair_energy[kBatch], force_over_r[kBatch];
  alignas(64) std::size_t neighbour[kBatch];

  const std::size_t n = list.particle_count();
  const Vec3* x = particles.x.data();
  Vec3* f = particles.f.data();
  const HalfNeighbourList::Entry* entries = list.entries();
  const auto& shifts = list.shifts();
  const double cutoff_squared = kernel.cutoff_squared;

  double energy = 0.0;
  double vxx = 0.0, vyy = 0.0, vzz = 0.0, vxy = 0.0, vxz = 0.0, vyz = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    double fxi = 0.0, fyi = 0.0, fzi = 0.0;
    const std::size_t end = list.first(i + 1);
    for (std::size_t k = list.first(i); k < end;) {
      const std::size_t batch_end = std::min(end, k + kBatch);
      int count = 0;
      // Every pair is written, and kept by advancing count only when inside.
      for (; k < batch_end; ++k) {
        const HalfNeighbourList::Entry e = entries[k];
        const std::size_t j = HalfNeighbourList::neighbour(e);
        const Vec3& s = shifts[HalfNeighbourList::shift_code(e)];
        const double ex = xi - x[j][0] + s[0];
        const double ey = yi - x[j][1] + s[1];
        const double ez = zi - x[j][2] + s[2];
        const double d2 = ex * ex + ey * ey + ez * ez;
        dx[count] = ex;
        dy[count] = ey;
        dz[count] = ez;
        r2[count] = d2;
        neighbour[count] = j;
        count += d2 < cutoff_squared ? 1 : 0;
      }
      for (int m = 0; m < count; ++m) {
        kernel.evaluate(i, neighbour[m], r2[m], pair_energy[m], force_over_r[m]);
      }
      for (int m = 0; m < count; ++m) {
        const std::size_t j = neighbour[m];
        const double fx = dx[m] * force_over_r[m];
        const double fy = dy[m] * force_over_r[m];
        const double fz = dz[m] * force_over_r[m];
        fxi += fx;
        fyi += fy;
        fzi += fz;
        f[j][0] -= fx;
        f[j][1] -= fy;
        f[j][2] -= fz;
        if constexpr (kTallied) {
          // A pair with a ghost is evaluated on both its ranks; each
          // tallies half, so that the sums over ranks count it once.
          const double w = j < n ? 1.0 : 0.5;
          energy += w * pair_energy[m];
          vxx += w * dx[m] * fx;
          vyy += w * dy[m] * fy;
          vzz += w * dz[m] * fz;
          vxy += w * dx[m] * fy;
          vxz += w * dx[m] * fz;
          vyz += w * dy[m] * fz;
        }
      }
    }
    f[i][0] += fxi;
    f[i][1] += fyi;
    f[i][2] += fzi;
  }
  PairResult result;
  if constexpr (kTallied) {
    result.energy = energy;
    result.virial = {vxx, vyy, vzz, vxy, vxz, vyz};
  }
  return result;
}

// Runs the loop with the tally chosen at run time, compiled for both.
template <class Kernel>
PairResult pair_force_loop(const Kernel& kernel, DpdParticles& particles,
                           const HalfNeighbourList& list, Tally tally) {
  if (tally == Tally::kEnergyAndVirial) {
    return pair_force_loop<Tally::kEnergyAndVirial>(kernel, particles, list);
  }
  return pair_force_loop<Tally::kForcesOnly>(kernel, particles, list);
}

}  // namespace pbms::dpd
