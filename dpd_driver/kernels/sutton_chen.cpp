#include "kernels/sutton_chen.hpp"

#include "kernels/fcc_crystal.hpp"
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
          pair_cutoff_param(),
          Param::real("p", Dimension::kNone,
                      "Embedding exponent: the embedding energy is -eps c rho^p; 0.5 is Sutton "
                      "and Chen's square root")
              .def(0.5)
              .above(0)
              .below(1),
          Param::real("knee", Dimension::kNone,
                      "Density, as a fraction of the perfect crystal's (lattice constant a), "
                      "below which the embedding flattens")
              .def(1.0)
              .above(0),
          Param::real("flattening", Dimension::kNone,
                      "Strength of the knee: the embedding gains flattening rho_c^p (knee - "
                      "rho/rho_c)^3 below it; 0 is Sutton and Chen's form, which ties the "
                      "surface energy to C44")
              .def(0.0)
              .at_least(0)};
}

std::unique_ptr<PairStyle> SuttonChen::create(const PairStyleParameters& params) {
  PairParameterReader read(kStyle, params);
  const double epsilon = read.required_positive("epsilon");
  const double a = read.required_positive("a");
  const double n = read.required_positive("n");
  const double m = read.required_positive("m");
  const double c = read.required_positive("c");
  const double cutoff = read.required_positive("cutoff");
  const double p = read.optional("p", 0.5);
  const double knee = read.optional("knee", 1.0);
  const double flattening = read.optional("flattening", 0.0);
  read.reject_unknown();
  return std::make_unique<SuttonChen>(epsilon, a, n, m, c, cutoff, p, knee, flattening);
}

namespace {

// Σ (a/r)^m over the sites of a perfect fcc crystal of lattice constant a
// within the cutoff, seen from one site.
double fcc_site_density(double a, double m, double cutoff) {
  const int reach = static_cast<int>(std::ceil(cutoff / a)) + 1;
  double rho = 0.0;
  for (int i = -reach; i <= reach; ++i) {
    for (int j = -reach; j <= reach; ++j) {
      for (int k = -reach; k <= reach; ++k) {
        for (const Vec3& b : kFccBasis) {
          const double dx = i + b[0], dy = j + b[1], dz = k + b[2];
          const double s2 = dx * dx + dy * dy + dz * dz;  // (r/a)^2
          if (s2 > 0.0 && s2 * a * a < cutoff * cutoff) rho += std::pow(s2, -0.5 * m);
        }
      }
    }
  }
  return rho;
}

}  // namespace

SuttonChen::SuttonChen(double epsilon, double a, double n, double m, double c, double cutoff,
                       double p, double knee, double flattening)
    : kernel_{epsilon, a * a, n, m, c, cutoff * cutoff, nullptr},
      cutoff_(cutoff),
      p_(p),
      crystal_density_(0.0),
      knee_(knee),
      knee_scale_(0.0) {
  if (!(epsilon > 0.0 && a > 0.0 && n > 0.0 && m > 0.0 && c > 0.0 && cutoff > 0.0)) {
    throw Error("pair style sutton_chen: epsilon, a, n, m, c and cutoff must be > 0");
  }
  if (!(p > 0.0 && p < 1.0)) {
    throw Error("pair style sutton_chen: the embedding exponent p must lie in (0, 1)");
  }
  if (!(knee > 0.0 && flattening >= 0.0)) {
    throw Error("pair style sutton_chen: the knee must be > 0 and the flattening >= 0");
  }
  crystal_density_ = fcc_site_density(a, m, cutoff);
  knee_scale_ = flattening * std::pow(crystal_density_, p);
}

double SuttonChen::power(double rho) const {
  return p_ == 0.5 ? std::sqrt(rho) : std::pow(rho, p_);
}

// An isolated particle (ρ = 0) has no pair that would read its slope.
double SuttonChen::power_slope(double rho, double powered) const {
  if (!(rho > 0.0)) return 0.0;
  return p_ == 0.5 ? 0.5 / powered : p_ * powered / rho;
}

double SuttonChen::knee_term(double rho) const {
  const double below = knee_ - rho / crystal_density_;
  return below > 0.0 ? knee_scale_ * below * below * below : 0.0;
}

double SuttonChen::knee_slope(double rho) const {
  const double below = knee_ - rho / crystal_density_;
  return below > 0.0 ? -3.0 * knee_scale_ * below * below / crystal_density_ : 0.0;
}

// Partners' neighbours are not listed, so their own sums are partial. Each
// takes the mean g of the particles it pairs with: those sit in the same
// crystal, and their densities are complete (partners included).
void SuttonChen::give_partners_neighbours_density(const HalfNeighbourList& list,
                                                  const DpdParticles& particles) {
  const std::size_t from = list.partners_from();
  const std::size_t size = embedding_slope_.size();
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
      sum[j - from] += embedding_slope_[i];
      ++count[j - from];
    }
  }
  for (std::size_t j = from; j < size; ++j) {
    const int c = count[j - from];
    embedding_slope_[j] = c > 0 ? sum[j - from] / c : 0.0;
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
  embedding_slope_.assign(particles.size(), 0.0);
  double embedded_sum = 0.0;
  const bool knee = knee_scale_ > 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double powered = power(density_[i]);
    embedding_slope_[i] = power_slope(density_[i], powered);
    embedded_sum += powered;
    if (knee) {
      embedded_sum += knee_term(density_[i]);
      embedding_slope_[i] += knee_slope(density_[i]);
    }
  }
  if (ghost_forward_) ghost_forward_(embedding_slope_);
  give_partners_neighbours_density(list, particles);
  kernel_.embedding_slope = embedding_slope_.data();

  PairResult result = pair_force_loop(kernel_, particles, list, tally, friction);
  if (tally != Tally::kForcesOnly) result.energy -= kernel_.epsilon * kernel_.c * embedded_sum;
  return result;
}

}  // namespace pbms::dpd
