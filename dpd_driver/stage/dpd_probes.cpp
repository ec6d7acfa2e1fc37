#include "dpd_probes.hpp"

#include <algorithm>
#include <limits>

#include "pbms/mpi/comm.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {

namespace {

void sum_all(MPI_Comm comm, double* data, int n) {
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, data, n, MPI_DOUBLE, MPI_SUM, comm), "MPI_Allreduce");
}

}  // namespace

DpdProbes::DpdProbes(const std::vector<DpdProbeSpec>& probes, const DpdModel& model) {
  const char* xyz[] = {"x", "y", "z"};
  for (const auto& p : probes) {
    const std::string& name = p.name;
    const std::string& kind = p.kind;
    Probe probe{};
    auto add = [&](const std::string& suffix, const std::string& unit) {
      std::string column = name;
      column += '.';
      column += suffix;
      columns_.push_back(std::move(column));
      units_.push_back(unit);
    };
    if (kind == "temperature") {
      probe.kind = Kind::kTemperature;
      columns_.push_back(name);
      units_.push_back("K");
    } else if (kind == "pressure") {
      probe.kind = Kind::kPressure;
      needs_potential_ = true;
      for (const char* c : {"xx", "yy", "zz", "xy", "xz", "yz"}) add(c, "bar");
      add("pressure", "bar");
    } else if (kind == "energy") {
      probe.kind = Kind::kEnergy;
      needs_potential_ = true;
      for (const char* c : {"kinetic", "potential", "internal", "total"}) add(c, "eV");
    } else if (kind == "momentum") {
      probe.kind = Kind::kMomentum;
      for (const char* c : xyz) add(c, "g/mol*Å/ps");
    } else if (kind == "slab_displacement") {
      probe.kind = Kind::kSlab;
      probe.mask = model.group_mask(p.group);
      for (const char* c : xyz) add(c, "Å");
    } else if (kind == "group_force") {
      probe.kind = Kind::kForce;
      probe.mask = model.group_mask(p.group);
      for (const char* c : xyz) add(c, "eV/Å");
    } else {
      probe.kind = Kind::kExtent;
      probe.mask = model.group_mask(p.group);
      probe.axis = p.axis;
      columns_.push_back(name);
      units_.push_back("Å");
    }
    probes_.push_back(probe);
  }
}

Vec3 DpdProbes::centre_of_mass(const DpdEngine& engine, std::uint32_t mask) {
  const DpdParticles& p = engine.particles();
  const OrthogonalBox& box = engine.domain().box();
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < engine.owned(); ++i) {
    if ((p.group_mask[i] & mask) == 0) continue;
    const double m = p.mass(i);
    for (int a = 0; a < 3; ++a) s[a] += m * (p.x[i][a] + p.image[i][a] * box.length(a));
    s[3] += m;
  }
  sum_all(engine.comm(), s, 4);
  if (s[3] == 0.0) return {0.0, 0.0, 0.0};
  return {s[0] / s[3], s[1] / s[3], s[2] / s[3]};
}

Vec3 DpdProbes::group_force(const DpdEngine& engine, std::uint32_t mask) {
  const DpdParticles& p = engine.particles();
  double f[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < engine.owned(); ++i) {
    if ((p.group_mask[i] & mask) == 0) continue;
    for (int a = 0; a < 3; ++a) f[a] += p.f[i][a];
  }
  sum_all(engine.comm(), f, 3);
  return {f[0], f[1], f[2]};
}

double DpdProbes::extent(const DpdEngine& engine, std::uint32_t mask, int axis) {
  const DpdParticles& p = engine.particles();
  const OrthogonalBox& box = engine.domain().box();
  double range[2] = {std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::infinity()};  // min, −max
  for (std::size_t i = 0; i < engine.owned(); ++i) {
    if ((p.group_mask[i] & mask) == 0) continue;
    const double x = p.x[i][axis] + p.image[i][axis] * box.length(axis);
    range[0] = std::min(range[0], x);
    range[1] = std::min(range[1], -x);
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, range, 2, MPI_DOUBLE, MPI_MIN, engine.comm()),
             "MPI_Allreduce");
  return range[0] == std::numeric_limits<double>::infinity() ? 0.0 : -range[1] - range[0];
}

std::vector<double> DpdProbes::sample(DpdEngine& engine, ThermoState& thermo) {
  std::vector<double> out;
  for (Probe& probe : probes_) {
    switch (probe.kind) {
      case Kind::kTemperature:
        out.push_back(thermo.temperature);
        break;
      case Kind::kPressure:
        out.insert(out.end(), thermo.pressure.begin(), thermo.pressure.end());
        out.push_back((thermo.pressure[0] + thermo.pressure[1] + thermo.pressure[2]) / 3.0);
        break;
      case Kind::kEnergy:
        out.insert(out.end(), {thermo.kinetic, thermo.potential, thermo.internal, thermo.total()});
        break;
      case Kind::kMomentum:
        out.insert(out.end(), thermo.momentum.begin(), thermo.momentum.end());
        break;
      case Kind::kSlab: {
        const Vec3 c = centre_of_mass(engine, probe.mask);
        if (!probe.has_reference) {
          probe.reference = c;
          probe.has_reference = true;
        }
        for (int a = 0; a < 3; ++a) out.push_back(c[a] - probe.reference[a]);
        break;
      }
      case Kind::kForce: {
        const Vec3 f = group_force(engine, probe.mask);
        out.insert(out.end(), {f[0], f[1], f[2]});
        break;
      }
      case Kind::kExtent:
        out.push_back(extent(engine, probe.mask, probe.axis));
        break;
    }
  }
  return out;
}

std::vector<double> DpdProbes::references() const {
  std::vector<double> out;
  for (const auto& p : probes_) {
    out.insert(out.end(),
               {p.has_reference ? 1.0 : 0.0, p.reference[0], p.reference[1], p.reference[2]});
  }
  return out;
}

void DpdProbes::set_references(const std::vector<double>& values) {
  for (std::size_t k = 0; k < probes_.size() && 4 * k + 3 < values.size(); ++k) {
    probes_[k].has_reference = values[4 * k] != 0.0;
    probes_[k].reference = {values[4 * k + 1], values[4 * k + 2], values[4 * k + 3]};
  }
}

}  // namespace pbms::dpd
