#include "pbms/coupling/conservation_ledger.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "pbms/coupling/scalar_across_programs.hpp"
#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/units.hpp"

namespace pbms::coupling {

ConservationLedger::ConservationLedger(MPI_Comm comm, std::vector<std::string> energies, bool walls)
    : comm_(comm), names_(std::move(energies)), walls_(walls), energies_(names_.size()) {}

ConservationLedger::Row ConservationLedger::motion_of(double time, const ParticleView& now) const {
  Row r;
  r.time = time;
  double twice_kinetic = 0.0;
  for (std::size_t i = 0; i < now.count; ++i) {
    const double m = now.mass[i];
    const Vec3& v = now.v[i];
    r.mass += m;
    twice_kinetic += m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (std::size_t a = 0; a < 3; ++a) r.momentum[a] += m * v[a];
  }
  r.kinetic = 0.5 * twice_kinetic * units::kMvv2e;
  r.energies.assign(names_.size(), 0.0);
  return r;
}

void ConservationLedger::add(Row mine) {
  if (mine.energies.size() != names_.size()) {
    throw Error(fmt::format("conservation ledger: a row with {} energies for {} names",
                            mine.energies.size(), names_.size()));
  }
  std::vector<double> sums{mine.mass, mine.momentum[0], mine.momentum[1], mine.momentum[2],
                           mine.kinetic};
  sums.insert(sums.end(), mine.energies.begin(), mine.energies.end());
  sums.insert(sums.end(), mine.wall_impulse.begin(), mine.wall_impulse.end());
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_DOUBLE,
                           MPI_SUM, comm_),
             "MPI_Allreduce (conservation ledger)");
  const std::size_t walls_at = 5 + names_.size();
  for (std::size_t a = 0; a < 3 && walls_; ++a) wall_impulse_[a].push_back(sums[walls_at + a]);
  time_.push_back(mine.time);
  mass_.push_back(sums[0]);
  for (std::size_t a = 0; a < 3; ++a) momentum_[a].push_back(sums[1 + a]);
  kinetic_.push_back(sums[4]);
  for (std::size_t k = 0; k < names_.size(); ++k) energies_[k].push_back(sums[5 + k]);
}

double ConservationLedger::momentum_drift(MPI_Comm inter) const {
  std::vector<double> mine;
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t k = 0; k < rows(); ++k) {
      mine.push_back(momentum_[a][k] - (walls_ ? wall_impulse_[a][k] : 0.0));
    }
  }
  std::vector<double> theirs(mine.size());
  swap_values(inter, comm_, mine, theirs);
  const std::size_t n = rows();
  double worst = 0.0;
  for (std::size_t a = 0; a < 3; ++a) {
    const double* p = &mine[a * n];
    const double* q = &theirs[a * n];
    for (std::size_t k = 0; k < n; ++k)
      worst = std::max(worst, std::abs(p[k] + q[k] - p[0] - q[0]));
  }
  return worst;
}

void ConservationLedger::report(StageResults& r, const std::string& prefix) const {
  const std::string table = prefix + "_ledger";
  r.add_column(table, "time", "ps", time_);
  r.add_column(table, "mass", "g/mol", mass_);
  r.add_column(table, "momentum_x", "g/mol*Å/ps", momentum_[0]);
  r.add_column(table, "momentum_y", "g/mol*Å/ps", momentum_[1]);
  r.add_column(table, "momentum_z", "g/mol*Å/ps", momentum_[2]);
  r.add_column(table, "kinetic_energy", "eV", kinetic_);
  for (std::size_t k = 0; k < names_.size(); ++k)
    r.add_column(table, names_[k], "eV", energies_[k]);
  if (walls_) {
    for (std::size_t a = 0; a < 3; ++a) {
      r.add_column(table, fmt::format("wall_impulse_{}", "xyz"[a]), "g/mol*Å/ps", wall_impulse_[a]);
    }
  }
}

void ConservationLedger::save(CheckpointArchive& a, const Row* pending) const {
  a.put("ledger/time", time_);
  a.put("ledger/mass", mass_);
  a.put("ledger/kinetic", kinetic_);
  for (std::size_t c = 0; c < 3; ++c) a.put(fmt::format("ledger/momentum_{}", c), momentum_[c]);
  for (std::size_t k = 0; k < names_.size(); ++k) a.put("ledger/" + names_[k], energies_[k]);
  for (std::size_t c = 0; c < 3 && walls_; ++c) {
    a.put(fmt::format("ledger/wall_impulse_{}", c), wall_impulse_[c]);
  }
  if (pending == nullptr) return;
  std::vector<double> row{pending->mass, pending->momentum[0], pending->momentum[1],
                          pending->momentum[2], pending->kinetic};
  row.insert(row.end(), pending->energies.begin(), pending->energies.end());
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, row.data(), static_cast<int>(row.size()), MPI_DOUBLE,
                           MPI_SUM, comm_),
             "MPI_Allreduce (conservation ledger)");
  row.insert(row.begin(), pending->time);
  a.put("ledger/pending", std::move(row));
}

ConservationLedger::Row ConservationLedger::load(const CheckpointArchive& a) {
  time_ = a.get("ledger/time");
  mass_ = a.get("ledger/mass");
  kinetic_ = a.get("ledger/kinetic");
  for (std::size_t c = 0; c < 3; ++c) momentum_[c] = a.get(fmt::format("ledger/momentum_{}", c));
  for (std::size_t k = 0; k < names_.size(); ++k) energies_[k] = a.get("ledger/" + names_[k]);
  for (std::size_t c = 0; c < 3 && walls_; ++c) {
    wall_impulse_[c] = a.get(fmt::format("ledger/wall_impulse_{}", c));
  }
  Row pending;
  pending.time = std::nan("");
  if (!a.has("ledger/pending")) return pending;
  // Every rank gets the archive, and add() sums the row over the ranks:
  // rank 0 takes the sums and the others nothing.
  const auto& row = a.get("ledger/pending");
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  const double share = rank == 0 ? 1.0 : 0.0;
  pending.time = row.at(0);
  pending.mass = share * row.at(1);
  for (std::size_t c = 0; c < 3; ++c) pending.momentum[c] = share * row.at(2 + c);
  pending.kinetic = share * row.at(5);
  pending.energies.assign(row.begin() + 6, row.end());
  for (double& e : pending.energies) e *= share;
  return pending;
}

}  // namespace pbms::coupling
