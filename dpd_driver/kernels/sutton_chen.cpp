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

// Partners' neighbours are not listed, so their own sums are partial. Each
// takes the mean g of the particles it pairs with: those sit in the same
// crystal, and their densities are complete (partners included).
void SuttonChen::give_partners_neighbours_density(const HalfNeighbourList& list,
                                                  const DpdParticles& particles) {
  const std::size_t from = list.partners_from();
  const std::size_t size = half_inverse_sqrt_density_.size();
  if (from >= size) return;
  std::vector<double> sum(size - from, 0.0);
  std::vector<int> count(size - from, 0);
  const HalfNeighbourList::Entry* entries = list.entries();
  for (std::size_t i = 0; i < list.particle_count(); ++i) {
    for (std::size_t k = list.first(i); k < list.first(i + 1); ++k) {
      const std::size_t j = HalfNeighbourList::neighbour(entries[k]);
      if (j < from) continue;
      const Vec3 d = list.separation(particles.x.data(), i, entries[k]);
      if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= kernel_.cutoff_squared) continue;
      sum[j - from] += half_inverse_sqrt_density_[i];
      ++count[j - from];
    }
  }
  for (std::size_t j = from; j < size; ++j) {
    const int c = count[j - from];
    half_inverse_sqrt_density_[j] = c > 0 ? sum[j - from] / c : 0.0;
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
  give_partners_neighbours_density(list, particles);
  kernel_.half_inverse_sqrt_density = half_inverse_sqrt_density_.data();

  PairResult result = pair_force_loop(kernel_, particles, list, tally, friction);
  if (tally != Tally::kForcesOnly) result.energy -= kernel_.epsilon * kernel_.c * embedding;
  return result;
}

}  // namespace pbms::dpd
