#include "engine/mpm_engine.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <limits>
#include <numeric>

#include "engine/point_migration.hpp"
#include "pbms/error.hpp"
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

std::vector<double> MpmEngine::own_rows() const {
  const grid::MaterialPoints& p = model_.points;
  std::vector<double> mine;
  mine.reserve(p.size() * kStateWidth);
  for (std::size_t i = 0; i < p.size(); ++i) {
    mine.push_back(static_cast<double>(p.id[i]));
    mine.insert(mine.end(), p.x[i].begin(), p.x[i].end());
    mine.insert(mine.end(), p.v[i].begin(), p.v[i].end());
    mine.insert(mine.end(), {p.mass[i], p.volume0[i]});
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) mine.push_back(p.F[i](r, c));
    }
    const grid::MaterialPointState& st = p.state[i];
    mine.insert(mine.end(), st.stress.voigt.begin(), st.stress.voigt.end());
    mine.insert(mine.end(),
                {st.density, st.plastic_strain, st.internal_energy,
                 static_cast<double>(p.material[i]), static_cast<double>(p.groups[i]), p.work[i]});
  }
  return mine;
}

void MpmEngine::restore_state(const State& state, std::int64_t steps) {
  const std::size_t n = state.rows.size() / kStateWidth;
  if (state.rows.size() % kStateWidth != 0 || static_cast<std::int64_t>(n) != total_points_) {
    throw Error(
        fmt::format("MPM engine: the checkpoint holds {} points, this run {}", n, total_points_));
  }
  std::vector<std::size_t> mine;
  if (static_cast<int>(state.counts.size()) == ranks_) {
    std::size_t from = 0;
    for (int r = 0; r < rank_; ++r) from += static_cast<std::size_t>(state.counts[r]);
    const auto count = static_cast<std::size_t>(state.counts[rank_]);
    for (std::size_t k = from; k < from + count; ++k) mine.push_back(k);
  } else {
    for (std::size_t k = 0; k < n; ++k) {
      const double* r = &state.rows[k * kStateWidth];
      if (partition_.owner_of({r[1], r[2], r[3]}) == rank_) mine.push_back(k);
    }
    std::sort(mine.begin(), mine.end(), [&](std::size_t a, std::size_t b) {
      return state.rows[a * kStateWidth] < state.rows[b * kStateWidth];
    });
  }
  grid::MaterialPoints points;
  for (const std::size_t k : mine) {
    const double* r = &state.rows[k * kStateWidth];
    grid::MaterialPointState st;
    std::copy(r + 18, r + 24, st.stress.voigt.begin());
    st.density = r[24];
    st.plastic_strain = r[25];
    st.internal_energy = r[26];
    points.add(static_cast<std::int64_t>(r[0]), {r[1], r[2], r[3]}, r[8], st,
               static_cast<int>(r[27]), static_cast<std::uint32_t>(r[28]));
    points.v.back() = {r[4], r[5], r[6]};
    points.mass.back() = r[7];
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) points.F.back()(a, b) = r[9 + 3 * a + b];
    }
    points.work.back() = r[29];
  }
  model_.points = std::move(points);
  steps_ = steps;
}

double MpmEngine::stable_time_step() const {
  return allreduce(comm_, solver_->stable_time_step(model_.points), MPI_MIN);
}

}  // namespace pbms::mpm
