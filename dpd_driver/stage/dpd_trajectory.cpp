#include "dpd_trajectory.hpp"

#include <cstddef>

#include "dpd_model.hpp"
#include "pbms/mpi/sorted_rows.hpp"

namespace pbms::dpd {
namespace {

std::vector<double> flat(const std::vector<Vec3>& a, std::ptrdiff_t n) {
  std::vector<double> out;
  out.reserve(3 * static_cast<std::size_t>(n));
  for (auto it = a.begin(); it != a.begin() + n; ++it)
    out.insert(out.end(), it->begin(), it->end());
  return out;
}

}  // namespace

DpdTrajectory::DpdTrajectory(MPI_Comm comm, std::filesystem::path file, bool forces,
                             bool internal_energy)
    : comm_(comm), file_(std::move(file)), forces_(forces), internal_energy_(internal_energy) {}

std::size_t DpdTrajectory::width() const {
  return 8 + (forces_ ? 3 : 0) + (internal_energy_ ? 1 : 0);
}

std::vector<double> DpdTrajectory::local_rows(const DpdEngine& engine) const {
  const DpdParticles& q = engine.particles();
  std::vector<double> rows;
  rows.reserve(engine.owned() * width());
  for (std::size_t i = 0; i < engine.owned(); ++i) {
    rows.insert(rows.end(), {static_cast<double>(q.id[i]), static_cast<double>(q.type[i]),
                             q.x[i][0], q.x[i][1], q.x[i][2], q.v[i][0], q.v[i][1], q.v[i][2]});
    if (forces_) rows.insert(rows.end(), {q.f[i][0], q.f[i][1], q.f[i][2]});
    if (internal_energy_) rows.push_back(q.internal_energy[i]);
  }
  return rows;
}

H5mdWriter::Options DpdTrajectory::options(const DpdEngine& engine) const {
  H5mdWriter::Options o;
  o.path = file_.string();
  o.creator_version = "dpd_driver";
  o.periodic = engine.domain().box().periodic;
  o.velocities = true;
  o.forces = forces_;
  o.internal_energy = internal_energy_;
  return o;
}

void DpdTrajectory::resume(const DpdEngine& engine, std::int64_t last_step) {
  int there = std::filesystem::exists(file_) ? 1 : 0;
  MPI_Bcast(&there, 1, MPI_INT, 0, comm_);
  if (there == 0) return;  // no frame before the checkpoint: the first write creates it
  const DpdParticles& q = engine.particles();
  const std::vector<std::int64_t> ids(q.id.begin(),
                                      q.id.begin() + static_cast<std::ptrdiff_t>(engine.owned()));
  h5md_ = H5mdWriter::reopen(comm_, options(engine), ids, last_step);
}

void DpdTrajectory::write_frame(const DpdEngine& engine, std::int64_t step, double dt) {
  const DpdParticles& q = engine.particles();
  const OrthogonalBox& box = engine.domain().box();
  const auto n = static_cast<std::ptrdiff_t>(engine.owned());
  const std::vector<std::int64_t> ids(q.id.begin(), q.id.begin() + n);
  if (!h5md_) {
    h5md_ = std::make_unique<H5mdWriter>(comm_, options(engine), ids,
                                         std::vector<int>(q.type.begin(), q.type.begin() + n));
  }
  const std::array<double, 3> edges{box.length(0), box.length(1), box.length(2)};
  const std::vector<double> u =
      internal_energy_
          ? std::vector<double>(q.internal_energy.begin(), q.internal_energy.begin() + n)
          : std::vector<double>{};
  h5md_->write_frame(step, static_cast<double>(step) * dt, edges, ids, flat(q.x, n), flat(q.v, n),
                     forces_ ? flat(q.f, n) : std::vector<double>{}, u);
}

void DpdTrajectory::keep_final_state(const DpdEngine& engine, const std::string& stage) const {
  const std::size_t w = width();
  const auto all = mpi::sorted_rows(comm_, local_rows(engine), w, mpi::RowsTo::kEveryRank);
  DpdParticles state;
  state.mass_per_type = engine.particles().mass_per_type;
  for (std::size_t r = 0; r + w <= all.size(); r += w) {
    state.add(static_cast<std::int64_t>(all[r]), static_cast<int>(all[r + 1]),
              {all[r + 2], all[r + 3], all[r + 4]}, {all[r + 5], all[r + 6], all[r + 7]});
    if (internal_energy_) state.internal_energy.back() = all[r + w - 1];
  }
  if (!internal_energy_) {
    // Internal energies travel only when written; carry them otherwise too.
    std::vector<double> rows;
    const DpdParticles& q = engine.particles();
    for (std::size_t i = 0; i < engine.owned(); ++i) {
      rows.insert(rows.end(), {static_cast<double>(q.id[i]), q.internal_energy[i]});
    }
    const auto u = mpi::sorted_rows(comm_, rows, 2, mpi::RowsTo::kEveryRank);
    for (std::size_t r = 0; r < state.size(); ++r) state.internal_energy[r] = u[2 * r + 1];
  }
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  dpd::keep_final_state(stage, std::move(state), rank == 0);
}

}  // namespace pbms::dpd
