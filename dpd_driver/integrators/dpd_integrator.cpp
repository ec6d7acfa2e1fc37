#include "integrators/dpd_integrator.hpp"

#include <algorithm>

#include "integrators/shardlow_sweep.hpp"
#include "kernels/pair_noise.hpp"
#include "pbms/error.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

double interaction_cutoff(const PairStyle& pair, const DpdIntegratorSettings& settings) {
  if (settings.scheme == DpdScheme::kNve) return pair.cutoff();
  return std::max(pair.cutoff(), settings.friction.cutoff);
}

bool friction_in_force_loop(const DpdIntegratorSettings& settings) {
  return settings.scheme == DpdScheme::kVelocityVerlet;
}

const DpdIntegratorSettings& checked_settings(const DpdIntegratorSettings& settings) {
  if (!(settings.dt > 0.0)) throw Error("DPD integrator: dt must be > 0 ps");
  if (settings.scheme == DpdScheme::kNve) return settings;
  if (!(settings.friction.gamma >= 0.0)) throw Error("DPD integrator: gamma must be >= 0 g/mol/ps");
  if (!(settings.friction.cutoff > 0.0)) throw Error("DPD integrator: DPD cutoff must be > 0 Å");
  if (settings.scheme == DpdScheme::kShardlowDpde && !(settings.heat_capacity > 0.0)) {
    throw Error("DPD integrator: DPDE needs a heat capacity > 0 eV/K");
  }
  if (settings.scheme != DpdScheme::kShardlowDpde && !(settings.friction.temperature >= 0.0)) {
    throw Error("DPD integrator: temperature must be >= 0 K");
  }
  return settings;
}

DpdIntegrator::DpdIntegrator(DpdParticles& particles, const OrthogonalBox& box, PairStyle& pair,
                             const DpdIntegratorSettings& settings)
    : particles_(particles),
      box_(box),
      pair_(pair),
      settings_(checked_settings(settings)),
      list_(interaction_cutoff(pair, settings), settings.skin, friction_in_force_loop(settings)),
      step_(settings.first_step) {
  if (settings_.scheme != DpdScheme::kNve) check_pair_noise_ids(particles_);
  if (is_shardlow(settings_.scheme)) {
    sweep_order_ =
        std::make_unique<ShardlowPairOrder>(box_, settings_.friction.cutoff, settings_.skin);
  }
  rebuild();
  compute_forces(Tally::kForcesOnly);
}

void DpdIntegrator::rebuild() {
  list_.build(particles_, box_);
  if (sweep_order_) sweep_order_->build(particles_, box_, [](const Vec3&) { return true; });
}

void DpdIntegrator::half_kick() {
  // f / m in eV/Å/(g/mol) is mvv2e Å/ps² too small.
  const double half_dt = 0.5 * settings_.dt / units::kMvv2e;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const double factor = half_dt / particles_.mass(i);
    for (int a = 0; a < 3; ++a) particles_.v[i][a] += factor * particles_.f[i][a];
  }
}

PairResult DpdIntegrator::compute_forces(Tally tally) {
  if (list_.needs_rebuild(particles_)) rebuild();
  particles_.zero_forces();
  if (friction_in_force_loop(settings_)) {
    // The velocities here are the half-step ones (see the header).
    return add_conservative_and_friction_forces(pair_, particles_, particles_.v, list_,
                                                settings_.friction, step_, settings_.dt, tally);
  }
  return pair_.compute(particles_, list_, tally);
}

void splitting_sweep(DpdParticles& particles, const ShardlowPairOrder& order,
                     const DpdIntegratorSettings& s, std::int64_t step,
                     const std::function<void(int colour)>& after_colour) {
  if (!is_shardlow(s.scheme)) return;
  for (int c = 0; c < ShardlowPairOrder::kColours; ++c) {
    if (s.scheme == DpdScheme::kShardlow) {
      shardlow_sweep(particles, order.colour(c), s.friction, step, s.dt);
    } else {
      shardlow_sweep_energy_conserving(particles, order.colour(c), s.friction, s.heat_capacity,
                                       step, s.dt);
    }
    if (after_colour) after_colour(c);
  }
}

PairResult DpdIntegrator::step(Tally tally) {
  const double dt = settings_.dt;
  if (sweep_order_) splitting_sweep(particles_, *sweep_order_, settings_, step_);
  half_kick();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    for (int a = 0; a < 3; ++a) particles_.x[i][a] += dt * particles_.v[i][a];
  }
  ++step_;
  const PairResult result = compute_forces(tally);
  half_kick();
  return result;
}

PairResult DpdIntegrator::potential() {
  scratch_forces_.swap(particles_.f);
  particles_.f.assign(particles_.size(), {0.0, 0.0, 0.0});
  const PairResult result = pair_.compute(particles_, list_, Tally::kEnergyAndVirial);
  scratch_forces_.swap(particles_.f);
  return result;
}

}  // namespace pbms::dpd
