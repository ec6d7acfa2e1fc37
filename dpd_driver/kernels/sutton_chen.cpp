#include "kernels/sutton_chen.hpp"

#include "kernels/pair_force_loop.hpp"
#include "kernels/pair_parameter_reader.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

std::vector<config::Param> SuttonChen::params() {
  using config::Param;
  using units::Dimension;
  return {Param::real("epsilon", Dimension::kEnergy, "Energy scale").require().above(0),
          Param::real("a", Dimension::kLength, "Length scale").require().above(0),
          Param::real("n", Dimension::kNone, "Pair repulsion exponent").require().above(0),
          Param::real("m", Dimension::kNone, "Density exponent").require().above(0),
          Param::real("c", Dimension::kNone, "Embedding weight").require().above(0),
          pair_cutoff_param()};
}

std::unique_ptr<PairStyle> SuttonChen::create(const PairStyleParameters& params) {
  PairParameterReader read(kStyle, params);
  const double epsilon = read.required_positive("epsilon");
  const double a = read.required_positive("a");
  const double n = read.required_positive("n");
  const double m = read.required_positive("m");
  const double c = read.required_positive("c");
  const double cutoff = read.required_positive("cutoff");
  read.reject_unknown();
  return std::make_unique<SuttonChen>(epsilon, a, n, m, c, cutoff);
}

SuttonChen::SuttonChen(double epsilon, double a, double n, double m, double c, double cutoff)
    : kernel_{epsilon, a * a, n, m, c, cutoff * cutoff, nullptr}, cutoff_(cutoff) {
  if (!(epsilon > 0.0 && a > 0.0 && n > 0.0 && m > 0.0 && c > 0.0 && cutoff > 0.0)) {
    throw Error("pair style sutton_chen: epsilon, a, n, m, c and cutoff must be > 0");
  }
}

PairResult SuttonChen::compute_forces(DpdParticles& particles, const HalfNeighbourList& list,
                                      Tally tally, const PairFrictionTerm* friction) {
  // Rows of the list are the owned particles; ghosts follow them.
  const std::size_t count = list.particle_count();
  density_.assign(particles.size(), 0.0);
  const Vec3* x = particles.x.data();
  const HalfNeighbourList::Entry* entries = list.entries();
  for (std::size_t i = 0; i < count; ++i) {
    double rho_i = 0.0;
    for (std::size_t k = list.first(i); k < list.first(i + 1); ++k) {
      const std::size_t j = HalfNeighbourList::neighbour(entries[k]);
      const Vec3 d = list.separation(x, i, entries[k]);
      const double dx = d[0], dy = d[1], dz = d[2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= kernel_.cutoff_squared) continue;
      const double phi = std::exp(kernel_.m * 0.5 * std::log(kernel_.a_squared / r2));
      rho_i += phi;
      density_[j] += phi;
    }
    density_[i] += rho_i;
  }

  // An owned density is complete now (its ghost partners were listed); a
  // ghost's is not, and its owner sends the g the force pass needs.
  half_inverse_sqrt_density_.assign(particles.size(), 0.0);
  double embedding = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double root = std::sqrt(density_[i]);
    embedding += root;
    // An isolated particle has no pair that would read its g.
    half_inverse_sqrt_density_[i] = root > 0.0 ? 0.5 / root : 0.0;
  }
  if (ghost_forward_) ghost_forward_(half_inverse_sqrt_density_);
  kernel_.half_inverse_sqrt_density = half_inverse_sqrt_density_.data();

  PairResult result = pair_force_loop(kernel_, particles, list, tally, friction);
  if (tally != Tally::kForcesOnly) result.energy -= kernel_.epsilon * kernel_.c * embedding;
  return result;
}

}  // namespace pbms::dpd
