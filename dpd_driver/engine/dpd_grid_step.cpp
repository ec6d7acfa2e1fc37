#include "engine/dpd_grid_step.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "materials/stressless_particle.hpp"
#include "pbms/error.hpp"
#include "pbms/grid/shape_function.hpp"
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
  init(grid, periodic);
}

void DpdGridStep::init(const grid::RegularGrid& grid, const std::array<bool, 3>& periodic) {
  const DpdEngine& engine = engine_;
  const DpdGridSettings& settings = settings_;
  if (engine.domain().size() > 1) {
    throw Error("DPD/MPM grid: the grid model runs on one dpd_driver rank for now");
  }
  const double cutoff = engine.settings().friction.cutoff;
  if (engine.settings().scheme != DpdScheme::kNve && !(settings.cell_size < cutoff)) {
    throw Error(fmt::format(
        "DPD/MPM grid: the cell edge {:g} Å must be below the DPD cutoff {:g} Å (seed §2.4)",
        settings.cell_size, cutoff));
  }
  const OrthogonalBox& box = engine.domain().box();
  partition_ = std::make_unique<grid::GridPartition>(grid, periodic, engine.domain().size());
  halo_ = std::make_unique<mpi::HaloSum>(engine.comm(), *partition_);
  mpm::GridPatch patch{grid, partition_->nodes_of(engine.domain().rank()), periodic, {}};
  if (!halo_->empty()) {
    patch.sum_shared = [this](double* data, int components, int stride) {
      halo_->sum(data, components, stride);
    };
  }
  std::vector<std::unique_ptr<mpm::Material>> materials;
  materials.push_back(std::make_unique<mpm::StresslessParticle>());
  mpm::SolverOptions opt;
  opt.flip = settings.flip;
  opt.units = mpm::UnitSystem::metal();
  // MPM's small-mass floor drops the momentum of the nodes it skips (the
  // momentum test of a thermostatted crystal lost 4e-5 of sum m|v| over 200
  // steps with it). A DPD particle's weights are products of linear ones,
  // so p_I / m_I stays accurate however light the node: only empty nodes
  // are skipped.
  opt.small_mass_fraction = 0.0;
  const DpdParticles& p = engine.particles();
  opt.reference_point_mass = *std::min_element(p.mass_per_type.begin(), p.mass_per_type.end());
  solver_ = std::make_unique<mpm::MpmSolver>(patch, grid::ShapeFunctionRegistry::create("linear"),
                                             std::move(materials), opt);
  for (const auto& g : settings.rigid) {
    bc_.point_velocities.push_back({g.mask, {true, true, true}, g.velocity});
    double mass = 0.0;
    for (std::size_t i = 0; i < engine.owned(); ++i) {
      if ((p.group_mask[i] & g.mask) != 0) mass += p.mass(i);
    }
    body_mass_.push_back(mass);
  }
  // The points' volume only enters a stress term, which is zero here.
  const double volume = box.volume() / static_cast<double>(std::max<std::size_t>(1, p.size()));
  for (std::size_t i = 0; i < engine.owned(); ++i) {
    mpm::MaterialPointState s;
    s.density = p.mass(i) / volume;
    points_.add(p.id[i], p.x[i], volume, s, 0, p.group_mask[i]);
    points_.mass.back() = p.mass(i);
  }
}

void DpdGridStep::load_points() {
  const DpdParticles& p = engine_.particles();
  forces_.resize(engine_.owned());
  for (std::size_t i = 0; i < engine_.owned(); ++i) {
    points_.id[i] = p.id[i];
    points_.x[i] = p.x[i];
    points_.v[i] = p.v[i];
    points_.mass[i] = p.mass(i);
    points_.groups[i] = p.group_mask[i];
    forces_[i] = p.f[i];
  }
  bc_.point_forces = forces_;
}

// The grid pass wraps positions on periodic axes; a jump of more than half
// the box is a crossing, which the particle's image count records.
void DpdGridStep::store_points() {
  DpdParticles& p = engine_.particles();
  const OrthogonalBox& box = engine_.domain().box();
  for (std::size_t i = 0; i < engine_.owned(); ++i) {
    for (int a = 0; a < 3; ++a) {
      if (!box.periodic[static_cast<std::size_t>(a)]) continue;
      const double jump = points_.x[i][a] - p.x[i][a];
      if (jump < -0.5 * box.length(a)) ++p.image[i][a];
      if (jump > 0.5 * box.length(a)) --p.image[i][a];
    }
    p.x[i] = points_.x[i];
    p.v[i] = points_.v[i];
  }
}

void DpdGridStep::push_free_bodies() {
  const DpdParticles& p = engine_.particles();
  // f / m in eV/Å/(g/mol) is mvv2e Å/ps² too small.
  const double dt = engine_.settings().dt / units::kMvv2e;
  for (std::size_t b = 0; b < settings_.rigid.size(); ++b) {
    const auto& g = settings_.rigid[b];
    if (!g.free_body || !(body_mass_[b] > 0.0)) continue;
    mpm::Vec3 force{0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < engine_.owned(); ++i) {
      if ((p.group_mask[i] & g.mask) == 0) continue;
      for (int a = 0; a < 3; ++a) force[a] += p.f[i][a];
    }
    for (int a = 0; a < 3; ++a)
      bc_.point_velocities[b].velocity[a] += dt * force[a] / body_mass_[b];
  }
}

void DpdGridStep::step() {
  compute_forces();
  map_to_grid();
  update_and_map_back();
  finish_step();
}

void DpdGridStep::compute_forces() {
  engine_.update_neighbours();
  engine_.compute_forces();
  push_free_bodies();
  load_points();
}

void DpdGridStep::map_to_grid() {
  const double dt = engine_.settings().dt;
  solver_->begin_step(points_);
  solver_->map_to_grid(points_, bc_, dt);
  solver_->complete_nodal_sums();
}

void DpdGridStep::update_and_map_back() {
  const double dt = engine_.settings().dt;
  solver_->update_nodes(bc_, dt);
  solver_->map_to_points(points_, bc_, dt);
  solver_->complete_remap_sums();
}

void DpdGridStep::finish_step() {
  solver_->update_stress_and_move(points_, bc_, engine_.settings().dt);
  store_points();
  engine_.count_step();
}

}  // namespace pbms::dpd
