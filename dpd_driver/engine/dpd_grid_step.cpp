#include "engine/dpd_grid_step.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/grid/shape_function.hpp"
#include "pbms/grid/stressless_particle.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {
namespace {

// The grid over the box: whole cells on periodic axes, a margin of cells
// beyond the box on free ones.
grid::RegularGrid grid_over(const OrthogonalBox& box, const DpdGridSettings& s) {
  const double h = s.cell_size;
  std::array<double, 3> origin{};
  std::array<int, 3> cells{};
  for (int a = 0; a < 3; ++a) {
    const auto aa = static_cast<std::size_t>(a);
    const double n = box.length(a) / h;
    if (box.periodic[aa]) {
      if (std::abs(n - std::round(n)) > 1e-9 * n) {
        throw Error(fmt::format(
            "DPD/MPM grid: the periodic box length {:g} Å along {} is not a whole number of "
            "{:g} Å cells; use a cell size of {:.10g} Å",
            box.length(a), "xyz"[a], h, box.length(a) / std::max(1.0, std::round(n))));
      }
      origin[aa] = box.lo[aa];
      cells[aa] = static_cast<int>(std::round(n));
    } else {
      origin[aa] = box.lo[aa] - s.free_axis_margin_cells * h;
      cells[aa] = static_cast<int>(std::ceil(n - 1e-9)) + 2 * s.free_axis_margin_cells;
    }
  }
  return grid::RegularGrid(origin, h, cells);
}

void allreduce_sum(MPI_Comm comm, double* data, int n) {
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, data, n, MPI_DOUBLE, MPI_SUM, comm), "MPI_Allreduce");
}

}  // namespace

DpdGridStep::DpdGridStep(DpdEngine& engine, const DpdGridSettings& settings)
    : engine_(engine), settings_(settings) {
  init(grid_over(engine.domain().box(), settings), engine.domain().box().periodic);
}

DpdGridStep::DpdGridStep(DpdEngine& engine, const DpdGridSettings& settings,
                         const grid::RegularGrid& grid, const std::array<bool, 3>& periodic)
    : engine_(engine), settings_(settings) {
  if (std::abs(grid.cell_size() - settings.cell_size) > 1e-12 * settings.cell_size) {
    throw Error(fmt::format("DPD/MPM grid: the cell size {:g} Å is not the grid's spacing {:g} Å",
                            settings.cell_size, grid.cell_size()));
  }
  // The engine wraps into the box and the solver into the grid: on a
  // periodic axis both must be the same interval.
  const OrthogonalBox& box = engine.domain().box();
  for (std::size_t a = 0; a < 3; ++a) {
    if (periodic[a] != box.periodic[a]) {
      throw Error(fmt::format(
          "DPD/MPM grid: the grid and the DPD box differ in periodicity along {}", "xyz"[a]));
    }
    const double tolerance = 1e-9 * box.length(static_cast<int>(a));
    if (box.periodic[a] && (std::abs(grid.origin()[a] - box.lo[a]) > tolerance ||
                            std::abs(grid.upper()[a] - box.hi[a]) > tolerance)) {
      throw Error(fmt::format(
          "DPD/MPM grid: along periodic {} the grid spans [{:g}, {:g}] Å, the DPD box [{:g}, "
          "{:g}] Å",
          "xyz"[a], grid.origin()[a], grid.upper()[a], box.lo[a], box.hi[a]));
    }
  }
  init(grid, periodic);
}

void DpdGridStep::init(const grid::RegularGrid& grid, const std::array<bool, 3>& periodic) {
  const DpdGridSettings& settings = settings_;
  const double cutoff = engine_.settings().friction.cutoff;
  if (engine_.settings().scheme != DpdScheme::kNve && !(settings.cell_size < cutoff)) {
    throw Error(fmt::format(
        "DPD/MPM grid: the cell edge {:g} Å must be below the DPD cutoff {:g} Å (seed §2.4)",
        settings.cell_size, cutoff));
  }
  const OrthogonalBox& box = engine_.domain().box();
  const int ranks = engine_.domain().size();
  partition_ = std::make_unique<grid::GridPartition>(grid, periodic, ranks);
  if (ranks > 1) engine_.decompose_as(*partition_);
  halo_ = std::make_unique<mpi::HaloSum>(engine_.comm(), *partition_);
  // One rank sums too: a periodic axis's last node layer is the first's
  // image and must hold the whole sum, as in an MPM run.
  grid::GridPatch patch{grid, partition_->nodes_of(engine_.domain().rank()), periodic, {}};
  if (!halo_->empty()) {
    patch.sum_shared = [this](double* data, int components, int stride) {
      halo_->sum(data, components, stride);
    };
  }
  std::vector<std::unique_ptr<grid::Material>> materials;
  materials.push_back(std::make_unique<grid::StresslessParticle>());
  grid::SolverOptions opt;
  opt.flip = settings.flip;
  opt.move = settings.move;
  if (settings.contact) opt.contact = grid::ContactField::kSurfaceFromOtherMass;
  opt.units = grid::UnitSystem::metal();
  opt.point_noun = "DPD particle";
  // MPM's small-mass floor drops the momentum of the nodes it skips (the
  // momentum test of a thermostatted crystal lost 4e-5 of sum m|v| over 200
  // steps with it). A DPD particle's weights are products of linear ones,
  // so p_I / m_I stays accurate however light the node: only empty nodes
  // are skipped.
  opt.small_mass_fraction = 0.0;
  const DpdParticles& p = engine_.particles();
  opt.reference_point_mass = *std::min_element(p.mass_per_type.begin(), p.mass_per_type.end());
  solver_ = std::make_unique<grid::MpmSolver>(
      std::move(patch), grid::ShapeFunctionRegistry::create("linear"), std::move(materials), opt);
  for (const auto& g : settings.rigid) {
    bc_.point_velocities.push_back({g.mask, {true, true, true}, g.velocity});
  }
  point_volume_ =
      box.volume() / static_cast<double>(std::max<std::int64_t>(1, engine_.total_particles()));
  load_points();
}

void DpdGridStep::load_points() {
  const DpdParticles& p = engine_.particles();
  const std::size_t n = engine_.owned();
  // Particles come and go with migration; the points' deformation and
  // state carry nothing for stressless particles, so fresh ones do.
  if (points_.size() != n) {
    points_ = grid::MaterialPoints{};
    grid::MaterialPointState s;
    for (std::size_t i = 0; i < n; ++i) {
      s.density = p.mass(i) / point_volume_;
      points_.add(p.id[i], p.x[i], point_volume_, s, 0, p.group_mask[i]);
    }
  }
  forces_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    points_.id[i] = p.id[i];
    points_.x[i] = solver_->grid().wrapped(p.x[i], solver_->patch().periodic);
    points_.v[i] = p.v[i];
    points_.mass[i] = p.mass(i);
    points_.groups[i] = p.group_mask[i];
    forces_[i] = p.f[i];
  }
  bc_.point_forces = forces_;
}

// The solver takes positions wrapped into the grid and wraps them again
// as it moves them. The engine keeps its own continuous, as velocity
// Verlet's drift does, and wraps them (counting images) when it rebuilds:
// a wrap here would make every step with a particle crossing a periodic
// face a rebuild, since the list's periodic shifts predate it.
void DpdGridStep::store_points() {
  DpdParticles& p = engine_.particles();
  const OrthogonalBox& box = engine_.domain().box();
  const grid::RegularGrid& g = solver_->grid();
  for (std::size_t i = 0; i < engine_.owned(); ++i) {
    const grid::Vec3 before = g.wrapped(p.x[i], box.periodic);
    for (std::size_t a = 0; a < 3; ++a) {
      double moved = points_.x[i][a] - before[a];
      if (box.periodic[a]) {
        const double length = box.length(static_cast<int>(a));
        if (moved > 0.5 * length) moved -= length;
        if (moved < -0.5 * length) moved += length;
      }
      p.x[i][a] += moved;
    }
    p.v[i] = points_.v[i];
  }
}

void DpdGridStep::set_rigid_velocity(std::uint32_t mask, const grid::Vec3& v) {
  for (std::size_t b = 0; b < settings_.rigid.size(); ++b) {
    if (settings_.rigid[b].mask == mask && !settings_.rigid[b].free_body) {
      bc_.point_velocities[b].velocity = v;
    }
  }
  engine_.set_group_velocity(mask, v);
}

std::vector<double> DpdGridStep::rigid_velocities() const {
  std::vector<double> out;
  for (const auto& pv : bc_.point_velocities)
    out.insert(out.end(), pv.velocity.begin(), pv.velocity.end());
  return out;
}

void DpdGridStep::restore_rigid_velocities(const std::vector<double>& v) {
  if (v.size() != 3 * bc_.point_velocities.size()) {
    throw Error(fmt::format("DPD/MPM grid: a checkpoint with {} rigid velocities for {} groups",
                            v.size() / 3, bc_.point_velocities.size()));
  }
  for (std::size_t b = 0; b < bc_.point_velocities.size(); ++b) {
    for (std::size_t a = 0; a < 3; ++a) bc_.point_velocities[b].velocity[a] = v[3 * b + a];
  }
}

// A free body's nodes hold the material that shares them as well as the
// body's own particles. Holding them at the body's velocity pushes that
// material, and setting the body's particles to it (rather than to what
// FLIP would give them) changes their momentum; the body pays for both
// when its velocity makes their sum zero. Momentum is then conserved to
// round-off (PIC or FLIP), where a velocity changed by the body's pair
// forces alone gave the material it sweeps along for free. Its own pair
// forces are in its nodes' momentum.
void DpdGridStep::balance_free_bodies() {
  constexpr std::size_t kWidth = 10;  // reaction, share momentum, particle momentum, held mass
  const std::size_t bodies = settings_.rigid.size();
  std::vector<double> sums(kWidth * bodies, 0.0);
  bool any = false;
  for (std::size_t b = 0; b < bodies; ++b) {
    if (!settings_.rigid[b].free_body) continue;
    any = true;
    double* row = &sums[kWidth * b];
    const auto& r = solver_->point_velocity_reactions()[b];
    const auto& share = solver_->held_share_momentum(b);
    for (std::size_t i = 0; i < points_.size(); ++i) {
      if (!points_.in_group(i, settings_.rigid[b].mask)) continue;
      for (std::size_t a = 0; a < 3; ++a) row[6 + a] += points_.mass[i] * points_.v[i][a];
    }
    for (std::size_t a = 0; a < 3; ++a) {
      row[a] = r[a];
      row[3 + a] = share[a];
    }
    row[9] = solver_->held_mass(b);
  }
  if (!any) return;
  allreduce_sum(engine_.comm(), sums.data(), static_cast<int>(sums.size()));
  const double dt = engine_.settings().dt;
  for (std::size_t b = 0; b < bodies; ++b) {
    const double* row = &sums[kWidth * b];
    if (!settings_.rigid[b].free_body || !(row[9] > 0.0)) continue;
    // Momentum the hold gives the nodes (reaction dt) and the body's
    // particles (held minus FLIP-PIC blend: the FLIP part's weight times
    // the nodes' old velocities weighted by the body's share, less its
    // particles' own momentum).
    grid::Vec3 dv{};
    for (std::size_t a = 0; a < 3; ++a) {
      const double pushed =
          row[a] * dt / units::kMvv2e + settings_.flip * (row[3 + a] - row[6 + a]);
      dv[a] = -pushed / row[9];
    }
    solver_->shift_held_nodes(bc_, b, dv, dt);
    for (std::size_t a = 0; a < 3; ++a) bc_.point_velocities[b].velocity[a] += dv[a];
  }
}

void DpdGridStep::step() {
  compute_forces();
  map_to_grid();
  update_nodes();
  map_back();
  map_at_midpoints();
  finish_step();
}

void DpdGridStep::compute_forces() {
  // Also here, for what changed since the last step (a thermostat's
  // velocities, which the ghosts' friction reads).
  refresh_neighbours();
  engine_.compute_forces(tally_);
  load_points();
}

void DpdGridStep::refresh_neighbours() {
  if (left_own_cells()) {
    engine_.rebuild_neighbours();
  } else {
    engine_.update_neighbours();
  }
}

bool DpdGridStep::list_needs_rebuild() {
  return left_own_cells() || engine_.list_is_stale();
}

bool DpdGridStep::left_own_cells() const {
  const DomainDecomposition& domain = engine_.domain();
  if (domain.size() == 1) return false;
  const DpdParticles& p = engine_.particles();
  int left = 0;
  for (std::size_t i = 0; i < engine_.owned() && left == 0; ++i) left = domain.owns(p.x[i]) ? 0 : 1;
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, &left, 1, MPI_INT, MPI_MAX, domain.comm()),
             "MPI_Allreduce (particles outside their cells)");
  return left != 0;
}

void DpdGridStep::map_to_grid() {
  const double dt = engine_.settings().dt;
  solver_->begin_step(points_);
  solver_->map_to_grid(points_, bc_, dt);
  solver_->complete_nodal_sums();
  solver_->mark_held_nodes(bc_);
}

void DpdGridStep::update_nodes() {
  solver_->update_nodes(bc_, engine_.settings().dt);
  balance_free_bodies();
}

void DpdGridStep::map_back() {
  solver_->map_to_points(points_, bc_, engine_.settings().dt);
  solver_->complete_remap_sums();
}

void DpdGridStep::map_at_midpoints() {
  solver_->update_stress_and_map_midpoints(points_, bc_, engine_.settings().dt);
  solver_->complete_midpoint_sums();
}

void DpdGridStep::finish_step() {
  solver_->move_from_midpoints(points_, bc_, engine_.settings().dt);
  store_points();
  engine_.count_step();
  // The engine is read between steps (thermo's energy and virial): its
  // ghosts must follow the particles that moved. One rank has none, and
  // its list stays valid as the positions stay continuous.
  if (engine_.domain().size() > 1) engine_.update_neighbours();
}

}  // namespace pbms::dpd
