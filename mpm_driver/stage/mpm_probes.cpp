#include "mpm_probes.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::mpm {

ProbeSpec ProbeSpec::from_yaml(const YAML::Node& n) {
  ProbeSpec s;
  s.name = n["name"].as<std::string>();
  s.kind = n["kind"].as<std::string>();
  if (n["group"]) s.group = n["group"].as<std::string>();
  if (n["axis"]) s.axis = n["axis"].as<std::string>();
  return s;
}

std::vector<ProbeSpec> ProbeSpec::list_from_yaml(const YAML::Node& probes) {
  std::vector<ProbeSpec> out;
  for (const auto& n : probes) out.push_back(from_yaml(n));
  return out;
}

MpmProbes::MpmProbes(const std::vector<ProbeSpec>& probes, const MpmModel& model,
                     bool metal_units) {
  const std::string energy = metal_units ? "eV" : "1";
  const std::string length = metal_units ? "Å" : "1";
  const std::string stress = metal_units ? "bar" : "1";
  const std::string force = metal_units ? "eV/Å" : "1";
  const std::string momentum = metal_units ? "g/mol Å/ps" : "1";
  const std::string volume = metal_units ? "Å^3" : "1";
  const char* xyz[] = {"x", "y", "z"};
  for (const ProbeSpec& spec : probes) {
    Probe p;
    p.name = spec.name;
    p.kind = spec.kind;
    p.sum_offset = n_sums_;
    p.max_offset = n_max_;
    p.column = columns_.size();
    if (spec.group) p.mask = model.group_mask(*spec.group);
    auto add = [&](const std::string& c, const std::string& u) {
      columns_.push_back(p.name + "." + c);
      units_.push_back(u);
    };
    if (p.kind == "energy") {
      // internal = stored at the start + stress work since; total =
      // kinetic + internal (see EnergySummary).
      for (const char* c : {"kinetic", "stored", "dissipated", "internal"}) add(c, energy);
      add("total", energy);
      energy_column_ = static_cast<int>(p.column + 4);
      n_sums_ += 4;
    } else if (p.kind == "momentum") {
      for (const char* c : xyz) add(c, momentum);
      n_sums_ += 3;
    } else if (p.kind == "mean_stress") {
      for (const char* c : {"xx", "yy", "zz", "yz", "xz", "xy"}) add(c, stress);
      add("pressure", stress);
      n_sums_ += 7;  // six volume-weighted components and the volume
    } else if (p.kind == "slab_displacement") {
      for (const char* c : xyz) add(c, length);
      n_sums_ += 4;  // mass-weighted position and the mass
    } else if (p.kind == "group_force") {
      const std::string& group = spec.group.value();
      for (size_t k = 0; k < model.point_velocity_groups.size(); ++k) {
        if (model.point_velocity_groups[k] == group) p.point_velocity = static_cast<int>(k);
      }
      if (p.point_velocity < 0) {
        throw Error(
            fmt::format("probe '{}': group '{}' has no group_velocity condition whose "
                        "reaction it could report",
                        p.name, group));
      }
      for (const char* c : xyz) add(c, force);
      n_sums_ += 3;
    } else if (p.kind == "group_extent") {
      const std::string& a = spec.axis;
      p.axis = a == "x" ? 0 : a == "y" ? 1 : 2;
      add(a, length);
      n_max_ += 2;  // max and -min
    } else if (p.kind == "group_volume") {
      add("volume", volume);
      n_sums_ += 1;
    }
    probes_.push_back(p);
  }
}

void MpmProbes::local(const grid::MaterialPoints& pts, const grid::MpmSolver& solver,
                      const grid::BoundaryConditions& /*bc*/, std::vector<double>& sums,
                      std::vector<double>& maxima) const {
  sums.assign(n_sums_, 0.0);
  maxima.assign(n_max_, -std::numeric_limits<double>::infinity());
  for (const auto& p : probes_) {
    double* s = sums.data() + p.sum_offset;
    if (p.kind == "energy") {
      const auto e = solver.energy(pts);
      s[0] = e.kinetic;
      s[1] = e.stored;
      s[2] = e.dissipated;
      s[3] = e.work;
    } else if (p.kind == "momentum") {
      for (size_t i = 0; i < pts.size(); ++i) {
        for (size_t a = 0; a < 3; ++a) s[a] += pts.mass[i] * pts.v[i][a];
      }
    } else if (p.kind == "mean_stress") {
      for (size_t i = 0; i < pts.size(); ++i) {
        if (!pts.in_group(i, p.mask)) continue;
        const double V = pts.volume(i);
        for (size_t c = 0; c < 6; ++c) s[c] += V * pts.state[i].stress.voigt[c];
        s[6] += V;
      }
    } else if (p.kind == "slab_displacement") {
      for (size_t i = 0; i < pts.size(); ++i) {
        if (!pts.in_group(i, p.mask)) continue;
        for (size_t a = 0; a < 3; ++a) s[a] += pts.mass[i] * pts.x[i][a];
        s[3] += pts.mass[i];
      }
    } else if (p.kind == "group_force") {
      const auto& r = solver.point_velocity_reactions();
      if (static_cast<size_t>(p.point_velocity) < r.size()) {
        for (size_t a = 0; a < 3; ++a) s[a] = r[static_cast<size_t>(p.point_velocity)][a];
      }
    } else if (p.kind == "group_extent") {
      double* m = maxima.data() + p.max_offset;
      for (size_t i = 0; i < pts.size(); ++i) {
        if (!pts.in_group(i, p.mask)) continue;
        m[0] = std::max(m[0], pts.x[i][p.axis]);
        m[1] = std::max(m[1], -pts.x[i][p.axis]);
      }
    } else if (p.kind == "group_volume") {
      for (size_t i = 0; i < pts.size(); ++i) {
        if (pts.in_group(i, p.mask)) s[0] += pts.volume(i);
      }
    }
  }
}

std::vector<double> MpmProbes::values(const std::vector<double>& sums,
                                      const std::vector<double>& maxima) const {
  std::vector<double> out(columns_.size(), 0.0);
  for (const auto& p : probes_) {
    const double* s = sums.data() + p.sum_offset;
    double* o = out.data() + p.column;
    if (p.kind == "energy") {
      o[0] = s[0];
      o[1] = s[1];
      o[2] = s[2];
      const double initial = reference_.empty() ? s[1] + s[2] : reference_[p.column + 3];
      o[3] = initial + s[3];
      o[4] = s[0] + o[3];
    } else if (p.kind == "momentum" || p.kind == "group_force") {
      std::copy(s, s + 3, o);
    } else if (p.kind == "mean_stress") {
      for (size_t c = 0; c < 6; ++c) o[c] = s[6] > 0.0 ? s[c] / s[6] : 0.0;
      o[6] = -(o[0] + o[1] + o[2]) / 3.0;
    } else if (p.kind == "slab_displacement") {
      for (size_t a = 0; a < 3; ++a) {
        const double com = s[3] > 0.0 ? s[a] / s[3] : 0.0;
        o[a] = reference_.empty() ? com : com - reference_[p.column + a];
      }
    } else if (p.kind == "group_extent") {
      const double* m = maxima.data() + p.max_offset;
      o[0] = m[0] + m[1];
    } else if (p.kind == "group_volume") {
      o[0] = s[0];
    }
  }
  return out;
}

void MpmProbes::set_reference(const std::vector<double>& values) {
  reference_ = values;
}

}  // namespace pbms::mpm
