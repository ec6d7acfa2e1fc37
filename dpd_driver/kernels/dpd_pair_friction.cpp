#include "kernels/dpd_pair_friction.hpp"

#include <cmath>

#include "kernels/pair_force_loop.hpp"
#include "kernels/pair_style.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

namespace {

// A pair formula that adds nothing, so that the friction term can run
// through the shared loop on its own, out to a DPD cutoff longer than the
// conservative one.
struct NoConservativeForce {
  double cutoff_squared;
  void evaluate(std::size_t /*i*/, std::size_t /*j*/, double /*r2*/, double& energy,
                double& force_over_r) const {
    energy = 0.0;
    force_over_r = 0.0;
  }
};

}  // namespace

PairFrictionTerm::PairFrictionTerm(const DpdPairFriction& friction,
                                   const std::vector<Vec3>& velocity_, std::int64_t step_,
                                   double dt)
    : velocity(velocity_.data()),
      noise(friction.seed, friction.noise),
      step(step_),
      cutoff(friction.cutoff),
      inverse_cutoff(1.0 / friction.cutoff),
      // γ (g/mol/ps) · v (Å/ps) is a momentum rate; mvv2e turns it into
      // eV/Å, and σ = sqrt(2 γ k_B T / mvv2e) in the same mass units.
      friction_factor(friction.gamma * units::kMvv2e),
      noise_factor(std::sqrt(2.0 * friction.gamma * units::kBoltzmann * friction.temperature *
                             units::kMvv2e / dt)) {}

void add_dissipative_random_forces(DpdParticles& particles, const std::vector<Vec3>& velocity,
                                   const HalfNeighbourList& list, const DpdPairFriction& friction,
                                   std::int64_t step, double dt) {
  const PairFrictionTerm term(friction, velocity, step, dt);
  pair_force_loop(NoConservativeForce{friction.cutoff * friction.cutoff}, particles, list,
                  Tally::kForcesOnly, &term);
}

PairResult add_conservative_and_friction_forces(PairStyle& pair, DpdParticles& particles,
                                                const std::vector<Vec3>& velocity,
                                                const HalfNeighbourList& list,
                                                const DpdPairFriction& friction, std::int64_t step,
                                                double dt, Tally tally) {
  if (friction.cutoff <= pair.cutoff()) {
    const PairFrictionTerm term(friction, velocity, step, dt);
    return pair.compute(particles, list, tally, &term);
  }
  PairResult result = pair.compute(particles, list, tally);
  add_dissipative_random_forces(particles, velocity, list, friction, step, dt);
  return result;
}

}  // namespace pbms::dpd
