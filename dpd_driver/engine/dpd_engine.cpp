#include "engine/dpd_engine.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/particle_migration.hpp"
#include "kernels/dpd_pair_friction.hpp"
#include "kernels/pair_noise.hpp"
#include "kernels/periodic_wrap.hpp"
#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/mpi/sorted_rows.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

namespace {

void allreduce_sum(MPI_Comm comm, double* data, int n) {
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, data, n, MPI_DOUBLE, MPI_SUM, comm), "MPI_Allreduce");
}

}  // namespace

DpdEngine::DpdEngine(MPI_Comm comm, const OrthogonalBox& box, std::unique_ptr<PairStyle> pair,
                     const DpdIntegratorSettings& settings, DpdParticles all)
    : domain_(comm, box, interaction_cutoff(*pair, settings) + settings.skin),
      pair_(std::move(pair)),
      settings_(checked_settings(settings)),
      ghosts_(domain_, interaction_cutoff(*pair_, settings) + settings.skin),
      list_(interaction_cutoff(*pair_, settings), settings.skin, friction_in_force_loop(settings)),
      step_(settings.first_step) {
  if (is_shardlow(settings_.scheme)) {
    sweep_order_ =
        std::make_unique<ShardlowPairOrder>(box, settings_.friction.cutoff, settings_.skin);
  }
  if (settings_.scheme != DpdScheme::kNve) check_pair_noise_ids(all);
  total_ = static_cast<std::int64_t>(all.size());
  wrap_periodic_axes(all, box, all.size());
  particles_.mass_per_type = all.mass_per_type;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (!domain_.owns(all.x[i])) continue;
    particles_.add(all.id[i], all.type[i], all.x[i], all.v[i]);
    particles_.image.back() = all.image[i];
    particles_.internal_energy.back() = all.internal_energy[i];
    particles_.group_mask.back() = all.group_mask[i];
  }
  owned_ = particles_.size();
  if (domain_.size() > 1) {
    pair_->set_ghost_forward([this](std::vector<double>& values) { ghosts_.forward(values); });
  }
  rebuild();
  compute_forces(Tally::kForcesOnly);
}

std::vector<double> DpdEngine::own_rows() const {
  std::vector<double> mine;
  mine.reserve(owned_ * kStateWidth);
  const DpdParticles& p = particles_;
  const std::vector<Vec3>& built = list_.positions_at_build();
  for (std::size_t i = 0; i < owned_; ++i) {
    mine.insert(mine.end(), {static_cast<double>(p.id[i]), static_cast<double>(p.type[i]),
                             static_cast<double>(p.group_mask[i])});
    for (int a = 0; a < 3; ++a) mine.push_back(p.x[i][a]);
    for (int a = 0; a < 3; ++a) mine.push_back(static_cast<double>(p.image[i][a]));
    for (int a = 0; a < 3; ++a) mine.push_back(p.v[i][a]);
    for (int a = 0; a < 3; ++a) mine.push_back(p.f[i][a]);
    mine.push_back(p.internal_energy[i]);
    for (int a = 0; a < 3; ++a) mine.push_back(i < built.size() ? built[i][a] : p.x[i][a]);
  }
  return mine;
}

namespace {

DpdParticles particles_of(const std::vector<double>& rows, const std::vector<std::size_t>& which,
                          bool at_build) {
  DpdParticles all;
  for (const std::size_t k : which) {
    const double* r = &rows[k * DpdEngine::kStateWidth];
    const Vec3 x = at_build ? Vec3{r[16], r[17], r[18]} : Vec3{r[3], r[4], r[5]};
    all.add(static_cast<std::int64_t>(r[0]), static_cast<int>(r[1]), x, {r[9], r[10], r[11]});
    all.group_mask.back() = static_cast<std::uint32_t>(r[2]);
    all.image.back() = {static_cast<int>(r[6]), static_cast<int>(r[7]), static_cast<int>(r[8])};
    all.f.back() = {r[12], r[13], r[14]};
    all.internal_energy.back() = r[15];
  }
  return all;
}

}  // namespace

void DpdEngine::restore_state(const State& state, std::int64_t step) {
  const std::size_t n = state.rows.size() / kStateWidth;
  if (state.rows.size() % kStateWidth != 0 || static_cast<std::int64_t>(n) != total_) {
    throw Error(
        fmt::format("DPD engine: the checkpoint holds {} particles, this run {}", n, total_));
  }
  // Which rows this rank takes: on as many ranks as wrote them its own, in
  // their order; else, in id order, those whose build position it owns.
  std::vector<std::size_t> mine;
  if (static_cast<int>(state.counts.size()) == domain_.size()) {
    std::size_t from = 0;
    for (int r = 0; r < domain_.rank(); ++r) from += static_cast<std::size_t>(state.counts[r]);
    const auto count = static_cast<std::size_t>(state.counts[domain_.rank()]);
    for (std::size_t k = from; k < from + count; ++k) mine.push_back(k);
  } else {
    std::vector<std::size_t> order(n);
    for (std::size_t k = 0; k < n; ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return state.rows[a * kStateWidth] < state.rows[b * kStateWidth];
    });
    const DpdParticles built = particles_of(state.rows, order, true);
    for (std::size_t i = 0; i < n; ++i) {
      if (domain_.owns(built.x[i])) mine.push_back(order[i]);
    }
  }
  // Ghosts, list and Shardlow sweep order are built from the positions the
  // writer built them from, so that they hold the same pairs in the same
  // sweep order; then the particles move on to where they are now.
  const std::vector<double> mass = particles_.mass_per_type;
  const DpdParticles now = particles_of(state.rows, mine, false);
  particles_ = particles_of(state.rows, mine, true);
  particles_.mass_per_type = mass;
  owned_ = particles_.size();
  step_ = step;
  rebuild();
  for (std::size_t i = 0; i < owned_; ++i) {
    particles_.x[i] = now.x[i];
    particles_.image[i] = now.image[i];
  }
  ghosts_.forward(particles_);
}

void DpdEngine::set_prescribed_groups(std::uint32_t mask) {
  if (mask != 0 && is_shardlow(settings_.scheme)) {
    throw Error(
        "DPD engine: rigid or frozen groups need the velocity_verlet or nve scheme (a Shardlow "
        "pair update would change their velocities)");
  }
  prescribed_ = mask;
}

void DpdEngine::set_group_velocity(std::uint32_t mask, const Vec3& v) {
  for (std::size_t i = 0; i < owned_; ++i) {
    if ((particles_.group_mask[i] & mask) != 0) particles_.v[i] = v;
  }
}

void DpdEngine::set_rigid_bodies(const std::vector<std::uint32_t>& masks) {
  std::uint32_t all = 0;
  for (const std::uint32_t m : masks) all |= m;
  set_prescribed_groups(prescribed_ | all);
  bodies_ = masks;
  body_mass_.assign(masks.size(), 0.0);
  for (std::size_t b = 0; b < masks.size(); ++b) {
    for (std::size_t i = 0; i < owned_; ++i) {
      if ((particles_.group_mask[i] & masks[b]) != 0) body_mass_[b] += particles_.mass(i);
    }
  }
  if (!masks.empty()) {
    allreduce_sum(comm(), body_mass_.data(), static_cast<int>(masks.size()));
  }
  body_force_.assign(3 * masks.size(), 0.0);
}

void DpdEngine::set_partners(const std::vector<Vec3>& x, const std::vector<Vec3>& v,
                             const std::vector<std::int64_t>& id, int type) {
  if (is_shardlow(settings_.scheme)) {
    throw Error("DPD engine: partner particles need the velocity_verlet or nve scheme");
  }
  partners_.truncate(0);
  for (std::size_t k = 0; k < x.size(); ++k) partners_.add(id[k], type, x[k], v[k]);
  with_partners_ = true;
  partners_changed_ = true;
}

void DpdEngine::move_partners(const std::vector<Vec3>& x, const std::vector<Vec3>& v) {
  for (std::size_t k = 0; k < partners_.size(); ++k) {
    partners_.x[k] = x[k];
    partners_.v[k] = v[k];
    const std::size_t i = partner_begin_ + k;
    for (std::size_t a = 0; a < 3; ++a) particles_.x[i][a] = x[k][a] + partner_offset_[k][a];
    particles_.v[i] = v[k];
  }
}

bool DpdEngine::list_is_stale() {
  double moved = list_.max_displacement_squared(particles_);
  if (domain_.size() > 1) {
    mpi::check(MPI_Allreduce(MPI_IN_PLACE, &moved, 1, MPI_DOUBLE, MPI_MAX, comm()),
               "MPI_Allreduce (neighbour list check)");
  }
  const double half_skin = 0.5 * list_.skin();
  return moved > half_skin * half_skin;
}

std::vector<Vec3> DpdEngine::partner_forces() const {
  const auto begin = particles_.f.begin() + static_cast<std::ptrdiff_t>(partner_begin_);
  return {begin, begin + static_cast<std::ptrdiff_t>(partners_.size())};
}

void DpdEngine::rebuild() {
  particles_.truncate(owned_);
  wrap_periodic_axes(particles_, domain_.box(), owned_);
  if (domain_.size() > 1) migrate_particles(domain_, particles_);
  owned_ = particles_.size();
  ghosts_.build(particles_, owned_);
  partner_begin_ = particles_.size();
  for (std::size_t k = 0; k < partners_.size(); ++k) {
    particles_.add(partners_.id[k], partners_.type[k], partners_.x[k], partners_.v[k]);
  }
  list_.build(particles_, domain_.list_box(), owned_, partner_begin_);
  // The build wrapped the partners into the box; moved partners keep it.
  partner_offset_.resize(partners_.size());
  for (std::size_t k = 0; k < partners_.size(); ++k) {
    for (std::size_t a = 0; a < 3; ++a) {
      partner_offset_[k][a] = particles_.x[partner_begin_ + k][a] - partners_.x[k][a];
    }
  }
  partners_changed_ = false;
  if (sweep_order_) {
    sweep_order_->build(particles_, domain_.list_box(),
                        [this](const Vec3& centre) { return domain_.owns(centre); });
  }
}

void DpdEngine::decompose_as(const grid::GridPartition& partition) {
  domain_ = DomainDecomposition(comm(), domain_.box(),
                                interaction_cutoff(*pair_, settings_) + settings_.skin, partition);
  particles_.truncate(owned_);
  wrap_periodic_axes(particles_, domain_.box(), owned_);
  if (domain_.size() > 1) redistribute_particles(domain_, particles_);
  owned_ = particles_.size();
  rebuild();
  compute_forces(Tally::kForcesOnly);
}

void DpdEngine::update_neighbours() {
  double moved = list_.max_displacement_squared(particles_);
  if (domain_.size() > 1) {
    mpi::check(MPI_Allreduce(MPI_IN_PLACE, &moved, 1, MPI_DOUBLE, MPI_MAX, comm()),
               "MPI_Allreduce (neighbour list check)");
  }
  const double half_skin = 0.5 * list_.skin();
  if (moved > half_skin * half_skin || partners_changed_) {
    rebuild();
  } else {
    ghosts_.forward(particles_);
  }
}

void DpdEngine::half_kick() {
  // f / m in eV/Å/(g/mol) is mvv2e Å/ps² too small.
  const double half_dt = 0.5 * settings_.dt / units::kMvv2e;
  for (std::size_t i = 0; i < owned_; ++i) {
    if ((particles_.group_mask[i] & prescribed_) != 0) continue;
    const double factor = half_dt / particles_.mass(i);
    for (int a = 0; a < 3; ++a) particles_.v[i][a] += factor * particles_.f[i][a];
  }
  if (bodies_.empty()) return;
  // A rigid body's internal forces cancel in the sum; what is left is the
  // push of everything else, shared by all its particles.
  std::fill(body_force_.begin(), body_force_.end(), 0.0);
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    for (std::size_t i = 0; i < owned_; ++i) {
      if ((particles_.group_mask[i] & bodies_[b]) == 0) continue;
      for (int a = 0; a < 3; ++a) body_force_[3 * b + a] += particles_.f[i][a];
    }
  }
  allreduce_sum(comm(), body_force_.data(), static_cast<int>(body_force_.size()));
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (!(body_mass_[b] > 0.0)) continue;
    for (std::size_t i = 0; i < owned_; ++i) {
      if ((particles_.group_mask[i] & bodies_[b]) == 0) continue;
      for (int a = 0; a < 3; ++a)
        particles_.v[i][a] += half_dt * body_force_[3 * b + a] / body_mass_[b];
    }
  }
}

PairResult DpdEngine::compute_forces(Tally tally) {
  particles_.zero_forces();
  if (friction_in_force_loop(settings_)) {
    // Half-step velocities (dpd_integrator.hpp), ghosts' included.
    last_tally_ = add_conservative_and_friction_forces(
        *pair_, particles_, particles_.v, list_, settings_.friction, step_, settings_.dt, tally);
  } else {
    last_tally_ = pair_->compute(particles_, list_, tally);
  }
  return last_tally_;
}

void DpdEngine::step() {
  if (sweep_order_) sweep_pairs();
  half_kick();
  drift();
  update_neighbours();
  compute_forces(Tally::kForcesOnly);
  half_kick();
}

void DpdEngine::drift() {
  const double dt = settings_.dt;
  for (std::size_t i = 0; i < owned_; ++i) {
    for (int a = 0; a < 3; ++a) particles_.x[i][a] += dt * particles_.v[i][a];
  }
  ++step_;
}

void DpdEngine::sweep_pairs() {
  if (!sweep_order_) return;
  const bool dpde = settings_.scheme == DpdScheme::kShardlowDpde;
  const bool decomposed = domain_.size() > 1;
  if (decomposed) {
    // The last half kick changed the owned velocities only.
    ghosts_.forward(particles_);
    if (dpde) ghosts_.forward(particles_.internal_energy);
  }
  std::function<void(int)> hand_back;
  if (decomposed) {
    hand_back = [&](int colour) {
      touched_.assign(particles_.size(), 0);
      for (const ShardlowPair& p : sweep_order_->colour(colour)) touched_[p.i] = touched_[p.j] = 1;
      ghosts_.reverse(particles_, touched_, dpde);
      ghosts_.forward(particles_);
      if (dpde) ghosts_.forward(particles_.internal_energy);
    };
  }
  splitting_sweep(particles_, *sweep_order_, settings_, step_, hand_back);
}

void DpdEngine::berendsen(double temperature, double tau, bool about_mean) {
  if (!(tau > 0.0)) throw Error("Berendsen thermostat: tau must be > 0 ps");
  double sums[6] = {};  // Σ m v², free particles, Σ m, Σ m v
  for (std::size_t i = 0; i < owned_; ++i) {
    if ((particles_.group_mask[i] & prescribed_) != 0) continue;
    const Vec3& v = particles_.v[i];
    const double m = particles_.mass(i);
    sums[0] += m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    sums[1] += 1.0;
    sums[2] += m;
    for (std::size_t a = 0; a < 3; ++a) sums[3 + a] += m * v[a];
  }
  allreduce_sum(comm(), sums, 6);
  Vec3 mean{0.0, 0.0, 0.0};
  if (about_mean && sums[2] > 0.0) {
    for (std::size_t a = 0; a < 3; ++a) mean[a] = sums[3 + a] / sums[2];
    sums[0] -= sums[2] * (mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]);
  }
  const double dof = 3.0 * sums[1] - 3.0;
  const double current = dof > 0.0 ? sums[0] * units::kMvv2e / (dof * units::kBoltzmann) : 0.0;
  if (!(current > 0.0)) {
    throw Error("Berendsen thermostat: the particles are at rest; assign velocities first");
  }
  const double lambda = std::sqrt(1.0 + settings_.dt / tau * (temperature / current - 1.0));
  for (std::size_t i = 0; i < owned_; ++i) {
    if ((particles_.group_mask[i] & prescribed_) != 0) continue;
    for (std::size_t a = 0; a < 3; ++a) {
      particles_.v[i][a] = mean[a] + lambda * (particles_.v[i][a] - mean[a]);
    }
  }
}

ThermoState DpdEngine::thermo(bool with_potential) {
  // count, K, Σu, 6 kinetic tensor, 3 momentum, U, 6 virial, free count, free K
  double s[21] = {};
  s[0] = static_cast<double>(owned_);
  for (std::size_t i = 0; i < owned_; ++i) {
    const double m = particles_.mass(i);
    const Vec3& v = particles_.v[i];
    const double mv2 = m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    s[1] += mv2;
    if ((particles_.group_mask[i] & prescribed_) == 0) {
      s[19] += 1.0;
      s[20] += mv2;
    }
    s[2] += particles_.internal_energy[i];
    s[3] += m * v[0] * v[0];
    s[4] += m * v[1] * v[1];
    s[5] += m * v[2] * v[2];
    s[6] += m * v[0] * v[1];
    s[7] += m * v[0] * v[2];
    s[8] += m * v[1] * v[2];
    for (int a = 0; a < 3; ++a) s[9 + a] += m * v[a];
  }
  if (with_potential) {
    scratch_forces_.swap(particles_.f);
    particles_.f.assign(particles_.size(), {0.0, 0.0, 0.0});
    const PairResult pr = pair_->compute(particles_, list_, Tally::kEnergyAndVirial);
    scratch_forces_.swap(particles_.f);
    s[12] = pr.energy;
    for (int c = 0; c < 6; ++c) s[13 + c] = pr.virial[c];
  }
  allreduce_sum(comm(), s, 21);
  ThermoState t;
  t.particles = s[0];
  t.kinetic = 0.5 * s[1] * units::kMvv2e;
  t.internal = s[2];
  // Frozen and rigid particles carry no thermal motion: the temperature is
  // that of the free ones (3 N - 3 degrees of freedom, as the thermostat's).
  const double dof = 3.0 * s[19] - 3.0;
  t.temperature = dof > 0.0 ? s[20] * units::kMvv2e / (dof * units::kBoltzmann) : 0.0;
  t.potential = s[12];
  const double volume = domain_.box().volume();
  for (int c = 0; c < 6; ++c) {
    t.pressure[c] = (s[3 + c] * units::kMvv2e + s[13 + c]) / volume * units::kBarPerEvPerA3;
  }
  for (int c = 0; c < 6; ++c) t.virial[c] = s[13 + c];
  t.momentum = {s[9], s[10], s[11]};
  return t;
}

}  // namespace pbms::dpd
