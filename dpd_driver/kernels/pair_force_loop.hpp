// The one loop over a half neighbour list that every conservative style runs,
// with the style's pair formula inlined through a template parameter, and,
// when the DPD thermostat is on, the dissipative and random pair forces
// evaluated in the same pass (the pair's separation, its cutoff test and the
// force scatter are then paid once).
//
// A Kernel provides
//   double cutoff_squared;                                    // Å^2
//   void evaluate(std::size_t i, std::size_t j, double r2,
//                 double& energy, double& force_over_r) const;
// where energy is the pair's contribution (eV) and force_over_r = −(dE/dr)/r
// (eV/Å^2), so that the force on i is force_over_r · r_ij. i and j let a
// many-body style use per-particle quantities; pair styles ignore them.
//
// A friction term reaches only pairs inside the kernel's cutoff, so its own
// cutoff must not be longer (PairStyle::compute checks). The tallied virial
// is the conservative one.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "kernels/dpd_pair_friction.hpp"
#include "kernels/dpd_particles.hpp"
#include "kernels/half_neighbour_list.hpp"
#include "kernels/pair_friction_coefficients.hpp"
#include "kernels/pair_style.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

template <Tally kTally, bool kFriction, class Kernel>
PairResult pair_force_loop(const Kernel& kernel, DpdParticles& particles,
                           const HalfNeighbourList& list, const PairFrictionTerm* friction) {
  constexpr bool kTallied = kTally != Tally::kForcesOnly;
  constexpr bool kVirial = kTally == Tally::kEnergyAndVirial;
  // Pairs pass in batches through separate loops: gather the pairs inside
  // the cutoff, evaluate the pair formula (and draw the noise), scatter the
  // forces. The middle loops have no memory dependence between pairs, so a
  // branch-free formula vectorises there; one fused loop would stay scalar.
  // A batch runs across particles, so that it is full: the noise draw works
  // on whole vectors of pairs, and a particle has fewer neighbours than
  // a batch holds.
  constexpr int kBatch = 64;
  alignas(64) double dx[kBatch], dy[kBatch], dz[kBatch], r2[kBatch];
  alignas(64) double pair_energy[kBatch], force_over_r[kBatch];
  alignas(64) std::size_t owner[kBatch], neighbour[kBatch];
  // The friction term's: the pair's ids and the two parts of its force over
  // r (pair_friction_coefficients.hpp).
  alignas(64) std::uint64_t id_pair[kBatch];
  alignas(64) double total_over_r[kBatch], drag[kBatch];

  const std::size_t n = list.particle_count();
  const Vec3* x = particles.x.data();
  Vec3* f = particles.f.data();
  const HalfNeighbourList::Entry* entries = list.entries();
  const auto& shifts = list.shifts();
  const double cutoff_squared = kernel.cutoff_squared;
  const Vec3* v = kFriction ? friction->velocity : nullptr;
  const std::uint64_t* list_ids = list.pair_ids();

  const std::size_t partners_from = list.partners_from();
  double energy = 0.0, partner_energy = 0.0;
  double vxx = 0.0, vyy = 0.0, vzz = 0.0, vxy = 0.0, vxz = 0.0, vyz = 0.0;

  // Not inlined into the gather loop below: inlined, its register demand
  // made GCC keep the gather loop's pointers (x, shifts, entries, the ids)
  // on the stack and reload them for every listed pair, which cost the
  // thermostat's loop, with one pointer more, about 8 % of its step.
  auto process = [&](int count) __attribute__((noinline)) {
    if (count == 0) return;
    for (int m = 0; m < count; ++m) {
      kernel.evaluate(owner[m], neighbour[m], r2[m], pair_energy[m], force_over_r[m]);
    }
    if constexpr (kFriction) {
      // Everything but the velocities, across pairs; the scatter loop
      // below, which visits every pair's i and j anyway, adds the
      // dissipative part from v_i − v_j without a second gather and store
      // of the relative velocities.
      pair_friction_coefficients(*friction, id_pair, r2, force_over_r, count, total_over_r, drag);
    }
    // Forces on the owner are summed while it stays the same, rather than
    // stored pair by pair into one f[i].
    std::size_t current = owner[0];
    double fxi = 0.0, fyi = 0.0, fzi = 0.0;
    double vxi = 0.0, vyi = 0.0, vzi = 0.0;
    if constexpr (kFriction) {
      vxi = v[current][0];
      vyi = v[current][1];
      vzi = v[current][2];
    }
    for (int m = 0; m < count; ++m) {
      const std::size_t i = owner[m];
      const std::size_t j = neighbour[m];
      if (i != current) {
        f[current][0] += fxi;
        f[current][1] += fyi;
        f[current][2] += fzi;
        fxi = fyi = fzi = 0.0;
        current = i;
        if constexpr (kFriction) {
          vxi = v[i][0];
          vyi = v[i][1];
          vzi = v[i][2];
        }
      }
      double pair_over_r = force_over_r[m];
      if constexpr (kFriction) {
        const double approach =
            dx[m] * (vxi - v[j][0]) + dy[m] * (vyi - v[j][1]) + dz[m] * (vzi - v[j][2]);
        pair_over_r = total_over_r[m] - drag[m] * approach;
      }
      const double fx = dx[m] * pair_over_r;
      const double fy = dy[m] * pair_over_r;
      const double fz = dz[m] * pair_over_r;
      fxi += fx;
      fyi += fy;
      fzi += fz;
      f[j][0] -= fx;
      f[j][1] -= fy;
      f[j][2] -= fz;
      if constexpr (kTallied) {
        // A pair with a ghost is evaluated on both its ranks; each
        // tallies half, so that the sums over ranks count it once. A pair
        // with a partner is evaluated on one rank only.
        const bool with_partner = j >= partners_from;
        const double w = j < n || with_partner ? 1.0 : 0.5;
        energy += w * pair_energy[m];
        partner_energy += with_partner ? pair_energy[m] : 0.0;
        if constexpr (kVirial) {
          const double wf = w * force_over_r[m];
          vxx += wf * dx[m] * dx[m];
          vyy += wf * dy[m] * dy[m];
          vzz += wf * dz[m] * dz[m];
          vxy += wf * dx[m] * dy[m];
          vxz += wf * dx[m] * dz[m];
          vyz += wf * dy[m] * dz[m];
        }
      }
    }
    f[current][0] += fxi;
    f[current][1] += fyi;
    f[current][2] += fzi;
  };

  int count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const std::size_t end = list.first(i + 1);
    for (std::size_t k = list.first(i); k < end; ++k) {
      // Every pair is written, and kept by advancing count only when inside.
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
      owner[count] = i;
      neighbour[count] = j;
      if constexpr (kFriction) id_pair[count] = list_ids[k];
      count += d2 < cutoff_squared ? 1 : 0;
      if (count == kBatch) {
        process(count);
        count = 0;
      }
    }
  }
  process(count);

  PairResult result;
  if constexpr (kTallied) {
    result.energy = energy;
    result.partner_energy = partner_energy;
  }
  if constexpr (kVirial) result.virial = {vxx, vyy, vzz, vxy, vxz, vyz};
  return result;
}

// Runs the loop with the tally and the friction term chosen at run time,
// compiled for all six.
template <class Kernel>
PairResult pair_force_loop(const Kernel& kernel, DpdParticles& particles,
                           const HalfNeighbourList& list, Tally tally,
                           const PairFrictionTerm* friction) {
  if (friction != nullptr) {
    // An empty list (a rank with no particles) may hold no id array at all.
    if (list.pair_ids() == nullptr && list.pair_count() > 0) {
      throw Error("DPD thermostat: the neighbour list was built without the pair ids");
    }
    switch (tally) {
      case Tally::kForcesOnly:
        return pair_force_loop<Tally::kForcesOnly, true>(kernel, particles, list, friction);
      case Tally::kEnergy:
        return pair_force_loop<Tally::kEnergy, true>(kernel, particles, list, friction);
      case Tally::kEnergyAndVirial:
        return pair_force_loop<Tally::kEnergyAndVirial, true>(kernel, particles, list, friction);
    }
  }
  switch (tally) {
    case Tally::kForcesOnly:
      return pair_force_loop<Tally::kForcesOnly, false>(kernel, particles, list, nullptr);
    case Tally::kEnergy:
      return pair_force_loop<Tally::kEnergy, false>(kernel, particles, list, nullptr);
    case Tally::kEnergyAndVirial:
      break;
  }
  return pair_force_loop<Tally::kEnergyAndVirial, false>(kernel, particles, list, nullptr);
}

}  // namespace pbms::dpd
