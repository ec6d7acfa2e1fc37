#include "md_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "md_setup.hpp"
#include "pbms/analysis/neck_history.hpp"
#include "pbms/analysis/neck_width.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"
#include "pbms/geometry/lattice_fill.hpp"
#include "pbms/geometry/region_yaml.hpp"

namespace pbms::md {

using config::OutputSpec;
using config::Param;
using units::Dimension;

config::StageKindSpec BodiesStage::spec() {
  config::StageKindSpec s;
  s.kind = "md_bodies";
  s.program = "md_driver";
  s.doc =
      "Free-standing crystals, each the lattice sites inside a region, at a temperature "
      "(Nose-Hoover NVT, free surfaces); necks between pairs of them over time (the MD "
      "reference for sintering)";
  s.material_kinds = {"eam_alloy", "eam_fs", "sutton_chen"};
  s.params = {
      Param::identifier("material", "Material to simulate").require().material(),
      Param::list_of(
          "bodies",
          Param::map("body",
                     {Param::identifier("name", "Body name").require(),
                      geometry::region_param("region", "Region the body's lattice fills").require(),
                      Param::real_list("lattice_origin", Dimension::kLength,
                                       "A lattice site; shift it to place a body apart from "
                                       "another")
                          .def(std::vector<double>{0.0, 0.0, 0.0})
                          .length(3, 3)},
                     "A crystal: the material's lattice sites inside a region"),
          "The bodies; none may share a site or sit closer than half a nearest-neighbour "
          "distance to another")
          .with_stage_names()
          .require()
          .length(1, 64),
      Param::real("lattice_constant", Dimension::kLength,
                  "Lattice constant of the bodies; defaults to the material's")
          .above(0)
          .referable(),
      Param::real("temperature", Dimension::kTemperature, "Temperature").def(298.0).above(0),
      Param::real("thermostat_time", Dimension::kTime, "Nose-Hoover damping time")
          .def(0.1)
          .above(0),
      Param::real("time", Dimension::kTime, "Time run").require().above(0),
      Param::real("timestep", Dimension::kTime, "MD time step").def(0.002).above(0).at_most(0.01),
      Param::integer("sample_every", "Steps between neck and temperature samples").def(50).above(0),
      Param::integer("trajectory_every", "Steps between H5MD frames; 0 writes none")
          .def(0)
          .at_least(0),
      Param::list_of(
          "necks",
          Param::map(
              "neck",
              {Param::identifier("name", "Key suffix: neck_<name>, neck_width_<name>, ...")
                   .require(),
               Param::identifier("first", "One body").require().names_entry_of({"bodies"}),
               Param::identifier("second", "The other body").require().names_entry_of({"bodies"})},
              "A neck between two bodies"),
          "Necks between bodies, by the rule of the concurrent stage's `necks` (seed §6.4) "
          "with the atoms' lattice constant")
          .def(std::vector<std::string>{}),
      Param::real("neck_stable_time", Dimension::kTime,
                  "neck_width_<name> is the mean over the run's last this much")
          .def(20.0)
          .above(0),
  };
  s.outputs = {
      {"atoms", OutputSpec::Shape::kScalar, "1", "Atoms in all bodies"},
      {"temperature", OutputSpec::Shape::kScalar, "K",
       "Mean temperature over the run's second half"},
      {"thermo", OutputSpec::Shape::kTable, "", "Time, temperature and potential energy"},
      {"neck_<name>", OutputSpec::Shape::kTable, "",
       "Time, neck width, the distance between the two bodies' centres and the closest "
       "approach of their atoms (capped at 2 a)"},
      {"neck_width_<name>", OutputSpec::Shape::kScalar, "Å",
       "The stable neck: mean width over the last neck_stable_time"},
      {"neck_final_<name>", OutputSpec::Shape::kScalar, "Å", "Width at the last sample"},
      {"contact_time_<name>", OutputSpec::Shape::kScalar, "ps",
       "First sample where an atom of each body is within 1.1 nearest-neighbour distances of "
       "the other (absent if never)"},
  };
  return s;
}

namespace {

struct NeckSpec {
  std::string name;
  int first = 0, second = 0;  // body indices
};

// The stage's parameters (schema: spec() above); times in ps, lengths in Å.
struct BodiesParams {
  std::string material;
  std::vector<std::string> names;
  std::vector<std::unique_ptr<geometry::Region>> regions;
  std::vector<geometry::Vec3> origins;
  std::optional<double> lattice_constant;
  double temperature = 0, tdamp = 0, time = 0, dt = 0, stable_time = 0;
  int64_t every = 0, traj_every = 0;
  std::vector<NeckSpec> necks;

  static BodiesParams from_yaml(const YAML::Node& p);
};

BodiesParams BodiesParams::from_yaml(const YAML::Node& p) {
  BodiesParams s;
  s.material = p["material"].as<std::string>();
  for (const auto& b : p["bodies"]) {
    s.names.push_back(b["name"].as<std::string>());
    s.regions.push_back(geometry::region_from_yaml(b["region"]));
    const auto o = b["lattice_origin"].as<std::vector<double>>();
    s.origins.push_back({o[0], o[1], o[2]});
  }
  if (p["lattice_constant"]) s.lattice_constant = p["lattice_constant"].as<double>();
  s.temperature = p["temperature"].as<double>();
  s.tdamp = p["thermostat_time"].as<double>();
  s.time = p["time"].as<double>();
  s.dt = p["timestep"].as<double>();
  s.every = p["sample_every"].as<int64_t>();
  s.traj_every = p["trajectory_every"].as<int64_t>();
  s.stable_time = p["neck_stable_time"].as<double>();
  const auto index = [&](const std::string& name) {
    return static_cast<int>(std::find(s.names.begin(), s.names.end(), name) - s.names.begin());
  };
  for (const auto& n : p["necks"]) {
    s.necks.push_back({n["name"].as<std::string>(), index(n["first"].as<std::string>()),
                       index(n["second"].as<std::string>())});
  }
  return s;
}

// The atoms body by body (ids run in this order) and each one's body.
struct Atoms {
  std::vector<geometry::Vec3> x;
  std::vector<int> body;
};

Atoms atoms_of(const BodiesParams& s, const MdMaterial& mat, double a) {
  Atoms atoms;
  for (std::size_t b = 0; b < s.regions.size(); ++b) {
    const auto sites = geometry::fill_lattice(geometry::lattice_style_from_name(mat.lattice),
                                              *s.regions[b], a, {}, s.origins[b]);
    if (sites.empty())
      throw StageFailure(fmt::format("body '{}' holds no lattice site", s.names[b]));
    atoms.x.insert(atoms.x.end(), sites.begin(), sites.end());
    atoms.body.insert(atoms.body.end(), sites.size(), static_cast<int>(b));
  }
  return atoms;
}

// Bodies that overlap would start with atoms on top of each other, which
// LAMMPS answers with forces that blow the crystal apart; refused instead.
void check_apart(const BodiesParams& s, const Atoms& atoms, double closest) {
  std::vector<std::vector<geometry::Vec3>> bodies(s.names.size());
  for (std::size_t i = 0; i < atoms.x.size(); ++i) {
    bodies[static_cast<std::size_t>(atoms.body[i])].push_back(atoms.x[i]);
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (std::size_t c = b + 1; c < bodies.size(); ++c) {
      const double d = analysis::closest_approach(bodies[b], bodies[c], closest);
      if (d >= closest) continue;
      throw StageFailure(fmt::format(
          "bodies '{}' and '{}' overlap: two of their atoms are {:.3f} Å apart, closer than "
          "{:.3f} Å (half a nearest-neighbour distance); move a region or its lattice_origin",
          s.names[b], s.names[c], d, closest));
    }
  }
}

// A LAMMPS data file of the atoms (rank 0), so that the script a stage
// writes replays with plain `lmp -in`.
void write_data(const std::filesystem::path& file, const Atoms& atoms, const MdMaterial& mat) {
  geometry::Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& p : atoms.x) {
    for (std::size_t c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  }
  std::ofstream out(file);
  out << fmt::format("pbms md_bodies: {} atoms\n\n{} atoms\n1 atom types\n\n", atoms.x.size(),
                     atoms.x.size());
  const char* axis[] = {"x", "y", "z"};
  for (std::size_t c = 0; c < 3; ++c) {
    out << fmt::format("{:.10f} {:.10f} {}lo {}hi\n", lo[c] - 1.0, hi[c] + 1.0, axis[c], axis[c]);
  }
  out << fmt::format("\nMasses\n\n1 {:.10g}\n\nAtoms # atomic\n\n", mat.mass);
  for (std::size_t i = 0; i < atoms.x.size(); ++i) {
    out << fmt::format("{} 1 {:.12g} {:.12g} {:.12g}\n", i + 1, atoms.x[i][0], atoms.x[i][1],
                       atoms.x[i][2]);
  }
  if (!out) throw StageFailure(fmt::format("could not write {}", file.string()));
}

// The LAMMPS set-up: the atoms from `data`, the potential, velocities at
// the temperature with each body at rest, Nose-Hoover NVT.
void start_lammps(Lammps& lmp, const BodiesParams& s, const Atoms& atoms, const MdMaterial& mat,
                  const std::filesystem::path& data, uint64_t seed) {
  lmp.command("units metal");
  lmp.command("atom_style atomic");
  lmp.command("atom_modify map array");
  lmp.command("boundary s s s");
  lmp.command("read_data " + data.string());
  set_pair_style(lmp, mat);
  lmp.command(fmt::format("velocity all create {} {} mom yes rot yes dist gaussian", s.temperature,
                          lammps_seed(seed, 11)));
  // Each body starts at rest as a whole, as an equilibrated DPD piece does:
  // drawn velocities leave every body a net drift (sqrt(kT/M), 0.02 Å/ps a
  // component for 8,589 atoms), which over 100 ps can carry two spheres
  // a few ångström apart before they touch.
  int64_t first = 1;
  for (std::size_t b = 0; b < s.names.size(); ++b) {
    const auto n = std::count(atoms.body.begin(), atoms.body.end(), static_cast<int>(b));
    lmp.command(fmt::format("group body{} id {}:{}", b, first, first + n - 1));
    lmp.command(fmt::format("velocity body{} zero linear", b));
    lmp.command(fmt::format("velocity body{} zero angular", b));
    first += n;
  }
  lmp.command(fmt::format("fix nvt all nvt temp {0} {0} {1}", s.temperature, s.tdamp));
  lmp.command(fmt::format("timestep {}", s.dt));
  lmp.command("thermo_style custom step temp pe");
  lmp.command("thermo 1000");
}

// Thermo and necks every sample. LAMMPS gathers the atoms to every rank;
// rank 0 alone measures the necks and reports.
class BodiesSampler {
 public:
  BodiesSampler(const BodiesParams& s, const Atoms& atoms, double a, bool root)
      : s_(s), atoms_(atoms), a_(a), root_(root) {
    for (const auto& n : s.necks) necks_.emplace_back(n.name, a);
  }

  void sample(Lammps& lmp, double t) {
    time_.push_back(t);
    temperature_.push_back(lmp.thermo("temp"));
    energy_.push_back(lmp.thermo("pe"));
    if (necks_.empty()) return;
    const auto flat = lmp.gather("x");
    if (!root_) return;
    std::vector<geometry::Vec3> x(atoms_.x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      x[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
    }
    for (std::size_t k = 0; k < necks_.size(); ++k) {
      std::vector<int> which(x.size(), -1);
      for (std::size_t i = 0; i < x.size(); ++i) {
        if (atoms_.body[i] == s_.necks[k].first) which[i] = 0;
        if (atoms_.body[i] == s_.necks[k].second) which[i] = 1;
      }
      necks_[k].add(t, analysis::neck_between(x, which, a_));
    }
  }

  void report(StageResults& r) const {
    r.add_scalar("atoms", static_cast<double>(atoms_.x.size()), "1");
    std::vector<double> late;
    for (std::size_t k = 0; k < time_.size(); ++k) {
      if (time_[k] >= 0.5 * time_.back()) late.push_back(temperature_[k]);
    }
    r.add_scalar("temperature", analysis::mean(late), "K");
    r.add_column("thermo", "time", "ps", time_);
    r.add_column("thermo", "temperature", "K", temperature_);
    r.add_column("thermo", "potential_energy", "eV", energy_);
    for (const auto& n : necks_) n.report(r, s_.stable_time);
  }

 private:
  const BodiesParams& s_;
  const Atoms& atoms_;
  double a_;
  bool root_;
  std::vector<analysis::NeckHistory> necks_;
  std::vector<double> time_, temperature_, energy_;
};

}  // namespace

void BodiesStage::run(StageContext& ctx) {
  const BodiesParams s = BodiesParams::from_yaml(ctx.params());
  const MdMaterial mat = material_of(ctx, s.material);
  const double a = s.lattice_constant.value_or(mat.lattice_constant);
  const Atoms atoms = atoms_of(s, mat, a);
  check_apart(s, atoms, 0.5 * a / std::sqrt(2.0));
  const auto data = ctx.stage_dir() / "bodies.data";
  if (ctx.rank() == 0) write_data(data, atoms, mat);
  MPI_Barrier(ctx.comm());

  Lammps lmp(ctx.comm(), ctx.stage_dir() / "bodies.log");
  start_lammps(lmp, s, atoms, mat, data, ctx.seed());
  BodiesSampler sampler(s, atoms, a, ctx.rank() == 0);
  TrajectoryRecorder traj(ctx, lmp, "bodies.h5md", s.traj_every, {false, false, false});
  const auto sample = [&](int64_t step) {
    const double t = static_cast<double>(step) * s.dt;
    traj.maybe_write(step, t);
    if (step % s.every == 0) sampler.sample(lmp, t);
  };
  lmp.command("run 0 post no");  // thermo and positions at step 0
  sample(0);
  const int64_t total = steps_for(s.time, s.dt);
  const int64_t chunk = std::gcd(s.every, s.traj_every > 0 ? s.traj_every : s.every);
  lmp.run(total, chunk, [&](int64_t done) {
    sample(done);
    ctx.progress(done, total, static_cast<double>(done) * s.dt, "bodies");
  });

  if (ctx.rank() != 0) return;
  lmp.write_script(ctx.stage_dir() / "bodies.in", "md_bodies " + ctx.stage());
  auto& r = ctx.results();
  r.files.push_back(ctx.stage() + "/bodies.in");
  if (traj.enabled()) r.files.push_back(traj.relative_path());
  sampler.report(r);
}

}  // namespace pbms::md
