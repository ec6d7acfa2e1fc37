#include "kernels/pair_table.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "kernels/pair_force_loop.hpp"
#include "kernels/pair_parameter_reader.hpp"
#include "pbms/error.hpp"

namespace pbms::dpd {

PairTableRows read_pair_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("pair table: cannot open '" + path + "'");
  PairTableRows rows;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    double r = 0.0, u = 0.0, f = 0.0;
    if (!(fields >> r)) continue;  // blank or comment-only line
    std::string extra;
    if (!(fields >> u >> f) || (fields >> extra) || !std::isfinite(r) || !std::isfinite(u) ||
        !std::isfinite(f)) {
      throw Error(path + ":" + std::to_string(line_number) +
                  ": expected three numbers r U F per row");
    }
    if (!rows.r.empty() && !(r > rows.r.back())) {
      throw Error(path + ":" + std::to_string(line_number) + ": r must increase from row to row");
    }
    if (!(r > 0.0)) throw Error(path + ":" + std::to_string(line_number) + ": r must be > 0");
    rows.r.push_back(r);
    rows.energy.push_back(u);
    rows.force.push_back(f);
  }
  if (rows.r.size() < 2) throw Error("pair table '" + path + "': needs at least two rows");
  return rows;
}

std::vector<config::Param> PairTable::params() {
  using config::Param;
  using units::Dimension;
  return {Param::file("file", "Rows r (Å), U (eV), F = -dU/dr (eV/Å)").require(),
          Param::real("cutoff", Dimension::kLength, "Cutoff; default the last row").above(0)};
}

std::unique_ptr<PairStyle> PairTable::create(const PairStyleParameters& params) {
  PairParameterReader read(kStyle, params);
  const std::string file = read.required_text("file");
  PairTableRows rows = read_pair_table(file);
  const double cutoff = read.optional("cutoff", rows.r.back());
  read.reject_unknown();
  if (!(cutoff > rows.r.front() && cutoff <= rows.r.back())) {
    read.fail("cutoff", "must lie in (" + std::to_string(rows.r.front()) + ", " +
                            std::to_string(rows.r.back()) + "] Å, the range of '" + file + "'");
  }
  return std::make_unique<PairTable>(std::move(rows), cutoff);
}

PairTable::PairTable(PairTableRows rows, double cutoff) : rows_(std::move(rows)), cutoff_(cutoff) {
  const std::size_t count = rows_.r.size();
  if (count < 2 || rows_.energy.size() != count || rows_.force.size() != count) {
    throw Error("pair table: needs at least two rows of r, U and F");
  }
  slope_.resize(count);
  for (std::size_t k = 0; k < count; ++k) slope_[k] = -rows_.force[k];

  const double spacing = (rows_.r.back() - rows_.r.front()) / static_cast<double>(count - 1);
  bool even = true;
  for (std::size_t k = 0; k < count; ++k) {
    const double expected = rows_.r.front() + spacing * static_cast<double>(k);
    if (std::abs(rows_.r[k] - expected) > 1e-9 * rows_.r.back()) even = false;
  }
  kernel_ = Kernel{rows_.r.data(),  rows_.energy.data(),        slope_.data(),  count,
                   rows_.r.front(), even ? 1.0 / spacing : 0.0, cutoff * cutoff};
}

std::size_t PairTable::Kernel::interval(double distance) const {
  if (inverse_spacing > 0.0) {
    const auto k = static_cast<std::size_t>((distance - r_first) * inverse_spacing);
    return std::min(k, rows - 2);
  }
  const auto upper = std::upper_bound(r, r + rows, distance);
  return std::min(static_cast<std::size_t>(upper - r), rows - 1) - 1;
}

void PairTable::Kernel::evaluate(std::size_t /*i*/, std::size_t /*j*/, double r2,
                                 double& pair_energy, double& force_over_r) const {
  const double distance = std::sqrt(r2);
  if (distance < r_first) {
    throw Error("pair table: pair distance " + std::to_string(distance) +
                " Å is below the first row of the table, " + std::to_string(r_first) + " Å");
  }
  const std::size_t k = interval(distance);
  const double h = r[k + 1] - r[k];
  const double t = (distance - r[k]) / h;
  const double t2 = t * t;
  const double t3 = t2 * t;
  const double u0 = energy[k], u1 = energy[k + 1];
  const double m0 = slope[k] * h, m1 = slope[k + 1] * h;
  pair_energy = (2.0 * t3 - 3.0 * t2 + 1.0) * u0 + (t3 - 2.0 * t2 + t) * m0 +
                (-2.0 * t3 + 3.0 * t2) * u1 + (t3 - t2) * m1;
  const double derivative = ((6.0 * t2 - 6.0 * t) * (u0 - u1) + (3.0 * t2 - 4.0 * t + 1.0) * m0 +
                             (3.0 * t2 - 2.0 * t) * m1) /
                            h;
  force_over_r = -derivative / distance;
}

void PairTable::interpolate(double r, double& energy, double& force) const {
  double force_over_r = 0.0;
  kernel_.evaluate(0, 0, r * r, energy, force_over_r);
  force = force_over_r * r;
}

PairResult PairTable::compute_forces(DpdParticles& particles, const HalfNeighbourList& list,
                                     Tally tally, const PairFrictionTerm* friction) {
  return pair_force_loop(kernel_, particles, list, tally, friction);
}

}  // namespace pbms::dpd
