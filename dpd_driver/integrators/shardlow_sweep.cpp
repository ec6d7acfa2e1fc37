#include "integrators/shardlow_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "kernels/pair_noise.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

namespace {

// PairTemperature(i, j) gives the k_B T (in g/mol·Å²/ps²) of σ² = 2 γ k_B T;
// KineticChange(i, j, ΔK) receives the kinetic energy (eV) the update added.
template <class PairTemperature, class KineticChange>
void sweep(DpdParticles& particles, std::span<const ShardlowPair> pairs,
           const DpdPairFriction& friction, std::int64_t step, double dt,
           PairTemperature pair_thermal_energy, KineticChange on_kinetic_change) {
  const double cutoff_squared = friction.cutoff * friction.cutoff;
  const double inverse_cutoff = 1.0 / friction.cutoff;
  const double half_dt = 0.5 * dt;
  const double sqrt_dt = std::sqrt(dt);
  const PairNoise noise(friction.seed, friction.noise);
  // θ depends on ids and step only, not on the updates before it: drawn in
  // vector batches ahead of the sequential pass (the same bits as one by
  // one), for every listed pair, the few beyond the cutoff included.
  constexpr std::size_t kBatch = 64;
  std::uint32_t id_low[kBatch], id_high[kBatch];
  double thetas[kBatch];
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const std::size_t slot = k % kBatch;
    if (slot == 0) {
      const std::size_t count = std::min(kBatch, pairs.size() - k);
      for (std::size_t m = 0; m < count; ++m) {
        // ShardlowPairOrder puts the lower id first; ids fit in 32 bits.
        id_low[m] = static_cast<std::uint32_t>(particles.id[pairs[k + m].i]);
        id_high[m] = static_cast<std::uint32_t>(particles.id[pairs[k + m].j]);
      }
      pair_noise_batch(noise, id_low, id_high, step, static_cast<int>(count), thetas);
    }
    const ShardlowPair& pair = pairs[k];
    const std::size_t i = pair.i, j = pair.j;
    const double m_i = particles.mass(i);
    const Vec3 d = pair.separation(particles.x.data());
    const double dx = d[0], dy = d[1], dz = d[2];
    const double r2 = dx * dx + dy * dy + dz * dz;
    if (r2 >= cutoff_squared) continue;
    const double r = std::sqrt(r2);
    const double e[3] = {dx / r, dy / r, dz / r};
    const double w_r = 1.0 - r * inverse_cutoff;
    const double m_j = particles.mass(j);
    const double inverse_reduced_mass = 1.0 / m_i + 1.0 / m_j;

    Vec3& v_i = particles.v[i];
    Vec3& v_j = particles.v[j];
    const double kinetic_before = m_i * (v_i[0] * v_i[0] + v_i[1] * v_i[1] + v_i[2] * v_i[2]) +
                                  m_j * (v_j[0] * v_j[0] + v_j[1] * v_j[1] + v_j[2] * v_j[2]);

    // Momentum transfers along e_ij, g/mol·Å/ps.
    const double friction_rate = friction.gamma * w_r * w_r;
    const double theta = thetas[slot];
    const double random_impulse = std::sqrt(2.0 * friction.gamma * pair_thermal_energy(i, j)) *
                                  w_r * theta * half_dt / sqrt_dt;
    auto approach = [&] {
      return e[0] * (v_i[0] - v_j[0]) + e[1] * (v_i[1] - v_j[1]) + e[2] * (v_i[2] - v_j[2]);
    };
    auto transfer = [&](double impulse) {
      for (int a = 0; a < 3; ++a) {
        v_i[a] += impulse * e[a] / m_i;
        v_j[a] -= impulse * e[a] / m_j;
      }
    };
    // First half step, explicit.
    transfer(-friction_rate * approach() * half_dt + random_impulse);
    // Second half step, implicit in the new approach speed w:
    //   w = w' + (1/μ)(−γ w_D w Δt/2 + random impulse).
    const double w_mid = approach();
    const double w_new = (w_mid + inverse_reduced_mass * random_impulse) /
                         (1.0 + inverse_reduced_mass * friction_rate * half_dt);
    transfer((w_new - w_mid) / inverse_reduced_mass);

    const double kinetic_after = m_i * (v_i[0] * v_i[0] + v_i[1] * v_i[1] + v_i[2] * v_i[2]) +
                                 m_j * (v_j[0] * v_j[0] + v_j[1] * v_j[1] + v_j[2] * v_j[2]);
    on_kinetic_change(i, j, 0.5 * (kinetic_after - kinetic_before) * units::kMvv2e);
  }
}

}  // namespace

void shardlow_sweep(DpdParticles& particles, std::span<const ShardlowPair> pairs,
                    const DpdPairFriction& friction, std::int64_t step, double dt) {
  const double thermal_energy = units::kBoltzmann * friction.temperature / units::kMvv2e;
  sweep(
      particles, pairs, friction, step, dt,
      [thermal_energy](std::size_t, std::size_t) { return thermal_energy; },
      [](std::size_t, std::size_t, double) {});
}

void shardlow_sweep_energy_conserving(DpdParticles& particles, std::span<const ShardlowPair> pairs,
                                      const DpdPairFriction& friction, double heat_capacity,
                                      std::int64_t step, double dt) {
  if (!(heat_capacity > 0.0)) throw Error("DPDE: heat capacity must be > 0 eV/K");
  std::vector<double>& u = particles.internal_energy;
  // k_B θ_ij with θ_ij = 2 / (1/θ_i + 1/θ_j) = (2 / C_v) u_i u_j / (u_i + u_j).
  const double scale = 2.0 * units::kBoltzmann / (heat_capacity * units::kMvv2e);
  auto pair_thermal_energy = [&](std::size_t i, std::size_t j) {
    if (!(u[i] > 0.0 && u[j] > 0.0)) {
      throw Error("DPDE: internal energy of particle " +
                  std::to_string(particles.id[u[i] > 0.0 ? j : i]) + " is " +
                  std::to_string(u[i] > 0.0 ? u[j] : u[i]) +
                  " eV, not positive; reduce the time step or raise the heat capacity");
    }
    return scale * u[i] * u[j] / (u[i] + u[j]);
  };
  auto share_out = [&](std::size_t i, std::size_t j, double kinetic_gain) {
    u[i] -= 0.5 * kinetic_gain;
    u[j] -= 0.5 * kinetic_gain;
  };
  sweep(particles, pairs, friction, step, dt, pair_thermal_energy, share_out);
}

}  // namespace pbms::dpd
