#include "engine/mpm_engine.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "engine/point_migration.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::mpm {
namespace {

int comm_rank(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

int comm_size(MPI_Comm comm) {
  int n = 1;
  MPI_Comm_size(comm, &n);
  return n;
}

double allreduce(MPI_Comm comm, double v, MPI_Op op) {
  double out = 0.0;
  mpi::check(MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, op, comm), "MPI_Allreduce");
  return out;
}

}  // namespace

MpmEngine::MpmEngine(MPI_Comm comm, MpmModel model, MaterialSet materials)
    : comm_(comm),
      rank_(comm_rank(comm)),
      ranks_(comm_size(comm)),
      model_(std::move(model)),
      total_points_(static_cast<std::int64_t>(model_.points.size())),
      partition_(model_.grid, model_.periodic, ranks_),
      halo_(comm, partition_) {
  keep_own_points();
  double min_mass = std::numeric_limits<double>::infinity();
  for (const double m : model_.points.mass) min_mass = std::min(min_mass, m);
  // The small-mass floor must be the same on every rank.
  model_.options.reference_point_mass = allreduce(comm_, min_mass, MPI_MIN);
  solver_ = std::make_unique<grid::MpmSolver>(
      patch(), grid::ShapeFunctionRegistry::create(model_.shape_function),
      std::move(materials.models), model_.options);
}

grid::GridPatch MpmEngine::patch() {
  grid::GridPatch p{model_.grid, partition_.nodes_of(rank_), model_.periodic, {}};
  if (!halo_.empty()) {
    p.sum_shared = [this](double* data, int components, int stride) {
      halo_.sum(data, components, stride);
    };
  }
  return p;
}

// Keeps the points this rank's cells hold, in id order, so that output and
// sums do not depend on the order erase() leaves behind.
void MpmEngine::keep_own_points() {
  grid::MaterialPoints& src = model_.points;
  std::vector<size_t> own;
  for (size_t i = 0; i < src.size(); ++i) {
    if (partition_.owner_of(src.x[i]) == rank_) own.push_back(i);
  }
  std::sort(own.begin(), own.end(), [&](size_t a, size_t b) { return src.id[a] < src.id[b]; });
  grid::MaterialPoints kept;
  for (const size_t i : own) {
    kept.add(src.id[i], src.x[i], src.volume0[i], src.state[i], src.material[i], src.groups[i]);
    kept.v.back() = src.v[i];
    kept.mass.back() = src.mass[i];
    kept.work.back() = src.work[i];
    kept.F.back() = src.F[i];
  }
  src = std::move(kept);
}

void MpmEngine::step(double dt) {
  begin_step();
  map_to_grid(dt);
  complete_nodal_sums();
  update_nodes(dt);
  map_to_points(dt);
  complete_remap_sums();
  update_stress_and_move(dt);
  migrate();
}

void MpmEngine::migrate() {
  ++steps_;
  if (ranks_ > 1) migrate_points(comm_, partition_, model_.points);
}

double MpmEngine::stable_time_step() const {
  return allreduce(comm_, solver_->stable_time_step(model_.points), MPI_MIN);
}

}  // namespace pbms::mpm
