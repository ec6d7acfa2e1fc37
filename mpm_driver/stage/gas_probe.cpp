#include "gas_probe.hpp"

#include <cmath>

#include "pbms/mpi/comm.hpp"
#include "pbms/units.hpp"

namespace pbms::mpm {

GasProbe::GasProbe(MPI_Comm comm, const coupling::GasParams& gas, int gas_material,
                   std::uint32_t away_mask)
    : comm_(comm), gas_(gas), material_(gas_material), away_(away_mask) {}

std::array<double, 3> GasProbe::total_impulse() const {
  std::array<double, 3> total = impulse_;
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, total.data(), 3, MPI_DOUBLE, MPI_SUM, comm_),
             "MPI_Allreduce (wall impulse)");
  return total;
}

void GasProbe::after_step(const MpmEngine& engine) {
  const grid::Vec3& j = engine.solver().node_constraint_impulse();
  for (std::size_t a = 0; a < 3; ++a) impulse_[a] += j[a];
  push_ += engine.solver().outer_face_push();
}

double GasProbe::wall_area(const MpmEngine& engine) {
  const auto& m = engine.model();
  const auto cells = m.grid.cells();
  double area = 0.0;
  for (std::size_t a = 0; a < 3; ++a) {
    if (m.periodic[a]) continue;
    double face = 1.0;
    for (std::size_t b = 0; b < 3; ++b) {
      if (b != a) face *= static_cast<double>(cells[b]) * m.grid.cell_size();
    }
    area += 2.0 * face;
  }
  return area;
}

// Volume-weighted means of P = -tr(sigma)/3, each point's volume its mass
// over its density; and the walls' mean pressure since the last sample,
// their inward push over that time and their area: a manometer's reading,
// which no point's state enters.
void GasProbe::sample(double t, const MpmEngine& engine) {
  const grid::MaterialPoints& p = engine.points();
  double sums[5] = {0.0, 0.0, 0.0, 0.0, push_};  // away: P V, V; all: P V, V; push
  push_ = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] != material_) continue;
    const double v = p.mass[i] / p.state[i].density;
    const double pv = -p.state[i].stress.trace() / 3.0 * v;
    if ((p.groups[i] & away_) != 0U) {
      sums[0] += pv;
      sums[1] += v;
    }
    sums[2] += pv;
    sums[3] += v;
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, sums, 5, MPI_DOUBLE, MPI_SUM, comm_),
             "MPI_Allreduce (gas pressure)");
  const double area = wall_area(engine);
  const double span = time_.empty() ? 0.0 : t - time_.back();
  wall_pressure_.push_back(span > 0.0 && area > 0.0
                               ? sums[4] * units::kMvv2e / (span * area) * units::kBarPerEvPerA3
                               : std::nan(""));
  time_.push_back(t);
  away_pressure_.push_back(sums[1] > 0.0 ? sums[0] / sums[1] : std::nan(""));
  all_pressure_.push_back(sums[3] > 0.0 ? sums[2] / sums[3] : std::nan(""));
}

void GasProbe::report(StageResults& r, std::int64_t gas_points) const {
  constexpr double kGPa = 1.0 / units::kBarPerGPa;
  std::vector<double> away, all, walls;
  double sum = 0.0, n = 0.0, wall_sum = 0.0, wall_n = 0.0;
  for (std::size_t k = 0; k < time_.size(); ++k) {
    away.push_back(away_pressure_[k] * kGPa);
    all.push_back(all_pressure_[k] * kGPa);
    walls.push_back(wall_pressure_[k] * kGPa);
    if (time_[k] < gas_.settle_time - 1e-9) continue;
    sum += away.back();
    n += 1.0;
    // A wall sample is the mean since the one before: it counts when that
    // span began after the settling.
    if (k > 0 && time_[k - 1] >= gas_.settle_time - 1e-9 && std::isfinite(walls.back())) {
      wall_sum += walls.back();
      wall_n += 1.0;
    }
  }
  r.add_column("gas_pressure_series", "time", "ps", time_);
  r.add_column("gas_pressure_series", "pressure_away_from_body", "GPa", away);
  r.add_column("gas_pressure_series", "pressure_all_gas", "GPa", all);
  r.add_column("gas_pressure_series", "pressure_on_walls", "GPa", walls);
  r.add_scalar("gas_points", static_cast<double>(gas_points), "1");
  const double target = gas_.pressure * kGPa;
  r.add_scalar("gas_pressure_target", target, "GPa");
  if (n > 0.0) {
    r.add_scalar("gas_pressure", sum / n, "GPa");
    if (target > 0.0) r.add_scalar("gas_pressure_error", sum / n / target - 1.0, "1");
  }
  if (wall_n > 0.0) {
    r.add_scalar("gas_pressure_on_walls", wall_sum / wall_n, "GPa");
    if (target > 0.0) {
      r.add_scalar("gas_pressure_on_walls_error", wall_sum / wall_n / target - 1.0, "1");
    }
  }
  const std::array<double, 3> total = total_impulse();
  r.add_scalar("wall_impulse", std::hypot(total[0], total[1], total[2]), "g/mol*Å/ps");
}

void GasProbe::save(CheckpointArchive& a) const {
  const std::array<double, 3> total = total_impulse();
  a.put("gas/wall_impulse", std::vector<double>(total.begin(), total.end()));
  a.put("gas/time", time_);
  a.put("gas/away", away_pressure_);
  a.put("gas/all", all_pressure_);
  a.put("gas/walls", wall_pressure_);
  double push = push_;
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, &push, 1, MPI_DOUBLE, MPI_SUM, comm_),
             "MPI_Allreduce (wall push)");
  a.put("gas/push", std::vector<double>{push});
}

void GasProbe::load(const CheckpointArchive& a) {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  const auto& total = a.get("gas/wall_impulse");
  for (std::size_t c = 0; c < 3; ++c) impulse_[c] = rank == 0 ? total.at(c) : 0.0;
  time_ = a.get("gas/time");
  away_pressure_ = a.get("gas/away");
  all_pressure_ = a.get("gas/all");
  wall_pressure_ = a.get("gas/walls");
  push_ = rank == 0 ? a.get("gas/push").at(0) : 0.0;
}

}  // namespace pbms::mpm
