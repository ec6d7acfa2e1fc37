#include "concurrent_mpm_part.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "engine/concurrent_mpm_side.hpp"
#include "engine/mpm_engine.hpp"
#include "materials/linear_elastic.hpp"
#include "pbms/coupling/body_handover.hpp"
#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/coupling/concurrent_probes.hpp"
#include "pbms/coupling/coupling_scheme.hpp"
#include "pbms/coupling/cross_program_link.hpp"
#include "pbms/coupling/exchange_report.hpp"
#include "pbms/coupling/scalar_across_programs.hpp"
#include "pbms/error.hpp"
#include "pbms/grid/for_each_node.hpp"
#include "pbms/io/grid_field_writer.hpp"
#include "pbms/io/h5md_writer.hpp"
#include "pbms/units.hpp"

namespace pbms::mpm {
namespace {

constexpr std::size_t kRowWidth = 9;  // id, x, v, mass, group bits

// The handed-over points on the shared grid. Rigid and frozen groups with
// points here are held at their velocity, as an MPM grip is.
MpmModel model_of(const coupling::ConcurrentParams& cp, const coupling::Handover& body,
                  const std::vector<std::string>& groups, double volume) {
  MpmModel m;
  m.grid = cp.grid;
  m.periodic = cp.periodic;
  m.options.flip = cp.flip;
  m.options.units = UnitSystem::metal();
  // The DPD part's nodal update skips only empty nodes; the shared nodes
  // must be updated alike.
  m.options.small_mass_fraction = 0.0;
  m.options.ddmp = cp.ddmp;
  m.options.ddmp_face_vanishing = cp.ddmp;
  m.group_names = groups;
  for (std::size_t r = 0; r + kRowWidth <= body.rows.size(); r += kRowWidth) {
    const double* d = &body.rows[r];
    MaterialPointState s;
    s.density = d[7] / volume;
    m.points.add(std::llround(d[0]), {d[1], d[2], d[3]}, volume, s, 0,
                 static_cast<std::uint32_t>(std::llround(d[8])));
    m.points.v.back() = {d[4], d[5], d[6]};
    m.points.mass.back() = d[7];
  }
  for (const auto& h : cp.held) {
    PointVelocity pv;
    pv.group_mask = m.group_mask(h.group);
    pv.axis = {true, true, true};
    pv.velocity = h.velocity;
    m.bc.point_velocities.push_back(pv);
  }
  return m;
}

// The nodes this rank writes: mass and velocity as the MPM part holds them
// after a step, both parts' sums on the interface band's nodes.
void write_grid(GridFieldWriter& out, const MpmEngine& engine, std::int64_t step, double t) {
  const MpmSolver& solver = engine.solver();
  const grid::NodeBox owned = engine.owned_nodes();
  const auto& local = solver.patch().nodes;
  std::vector<double> mass, vel;
  grid::for_each_node(owned, [&](const std::array<int, 3>& ijk) {
    const auto li = static_cast<std::size_t>(local.local_index(ijk));
    mass.push_back(solver.nodal_mass(li));
    const auto& v = solver.nodal_velocity(li);
    vel.insert(vel.end(), v.begin(), v.end());
  });
  out.write_frame(step, t,
                  {{"mass", "g/mol", 1, mass.data()}, {"velocity", "Å/ps", 3, vel.data()}});
}

// The MPM part's points, one H5MD frame, each rank writing its own.
void write_points(H5mdWriter& out, const MpmEngine& engine, std::int64_t step, double t) {
  const MaterialPoints& p = engine.points();
  std::vector<double> x, v;
  for (std::size_t i = 0; i < p.size(); ++i) {
    x.insert(x.end(), p.x[i].begin(), p.x[i].end());
    v.insert(v.end(), p.v[i].begin(), p.v[i].end());
  }
  const auto& g = engine.model().grid;
  out.write_frame(
      step, t,
      {g.upper()[0] - g.origin()[0], g.upper()[1] - g.origin()[1], g.upper()[2] - g.origin()[2]},
      p.id, x, v);
}

coupling::ParticleView view_of(const MaterialPoints& p) {
  return {p.size(), p.id, p.x, p.v, p.mass, p.groups};
}

}  // namespace

config::StageKindSpec ConcurrentMpmPart::spec() {
  config::StageKindSpec s;
  s.kind = "concurrent_mpm_part";
  s.program = "mpm_driver";
  s.doc = "mpm_driver's part of a dpd_driver `concurrent` stage";
  s.internal = true;
  return s;
}

void ConcurrentMpmPart::run(StageContext& ctx) {
  const coupling::ConcurrentParams cp = coupling::concurrent_params(ctx.params());
  const MPI_Comm inter = ctx.peer("dpd_driver");
  if (inter == MPI_COMM_NULL) {
    throw Error(fmt::format("stage '{}': dpd_driver is not running", ctx.stage()));
  }
  const coupling::Handover body = coupling::take_over(inter, ctx.comm());
  const YAML::Node header = YAML::Load(body.header);
  const auto groups = header["groups"].as<std::vector<std::string>>();
  const auto lo = header["band_lo"].as<std::vector<int>>();
  const auto hi = header["band_hi"].as<std::vector<int>>();
  const grid::NodeBox band{{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
  const double reach = header["reach"].as<double>();
  const YAML::Node material = ctx.material(cp.material);
  const double a = cp.lattice_constant.value_or(material["lattice_constant"].as<double>());
  const double volume = a * a * a / 4.0;  // one fcc site

  MaterialSet materials;
  materials.models.push_back(std::make_unique<LinearElastic>(cp.youngs_modulus, cp.poisson_ratio));
  materials.names.push_back("continuum");
  materials.density.push_back(material["mass"].as<double>() / volume);
  MpmEngine engine(ctx.comm(), model_of(cp, body, groups, volume), std::move(materials));
  ConcurrentMpmSide side(engine, cp.time_step, header["skin"].as<double>());
  int remote = 0;
  MPI_Comm_remote_size(inter, &remote);
  const grid::GridPartition theirs(cp.grid, cp.periodic, remote);
  coupling::CrossProgramLink link(inter, side, engine.partition(), theirs, band, reach);
  coupling::CouplingScheme scheme({&side}, link, cp.interface);

  coupling::ConcurrentProbes probes(ctx.comm(), cp, groups, 0.5 * a, view_of(engine.points()));
  const double mass = static_cast<double>(engine.total_points()) * material["mass"].as<double>();
  (void)coupling::swap_scalar(inter, ctx.comm(), mass);
  std::vector<double> stored, dissipated, point_mass;
  auto sample = [&](std::int64_t n) {
    const auto v = view_of(engine.points());
    probes.sample(n, v);
    for (std::size_t k = 0; k < 3; ++k) {
      (void)coupling::swap_scalar(inter, ctx.comm(), probes.momentum()[k]);
    }
    if (cp.tension) {
      const MpmModel& m = engine.model();
      std::vector<std::uint32_t> masks;
      for (const auto& pv : m.bc.point_velocities) masks.push_back(pv.group_mask);
      const auto& reactions = engine.solver().point_velocity_reactions();
      for (const auto& grip : {cp.tension->left_grip, cp.tension->right_grip}) {
        const double f = coupling::grip_force(ctx.comm(), reactions, masks, m.group_mask(grip),
                                              cp.tension->axis);
        (void)coupling::swap_scalar(inter, ctx.comm(), f);
      }
      // Σ σ V along the axis, bar Å^3 to eV.
      const MaterialPoints& q = engine.points();
      double sv = 0.0;
      for (std::size_t i = 0; i < q.size(); ++i) {
        sv += q.volume(i) * q.state[i].stress.voigt[static_cast<std::size_t>(cp.tension->axis)];
      }
      MPI_Allreduce(MPI_IN_PLACE, &sv, 1, MPI_DOUBLE, MPI_SUM, ctx.comm());
      (void)coupling::swap_scalar(inter, ctx.comm(), sv / units::kBarPerEvPerA3);
    }
    if (cp.opening) {
      (void)coupling::swap_values(inter, ctx.comm(), probes.opening_moments(v));
    }
    const EnergySummary energy = engine.solver().energy(engine.points());
    double e[2] = {energy.stored, energy.dissipated};
    MPI_Allreduce(MPI_IN_PLACE, e, 2, MPI_DOUBLE, MPI_SUM, ctx.comm());
    stored.push_back(e[0]);
    dissipated.push_back(e[1]);
    point_mass.push_back(probes.mass());
  };
  std::unique_ptr<GridFieldWriter> grid_out;
  std::unique_ptr<H5mdWriter> points_out;
  if (cp.particles_every > 0) {
    H5mdWriter::Options o;
    o.path = (ctx.stage_dir() / "mpm_particles.h5md").string();
    o.creator_version = "mpm_driver (concurrent)";
    o.periodic = cp.periodic;
    o.velocities = true;
    points_out = std::make_unique<H5mdWriter>(ctx.comm(), o, engine.points().id,
                                              std::vector<int>(engine.points().size(), 1));
    write_points(*points_out, engine, 0, 0.0);
    grid_out = std::make_unique<GridFieldWriter>(
        ctx.comm(), (ctx.stage_dir() / "mpm_grid").string(), cp.grid, engine.owned_nodes());
  }
  probes.track(0, view_of(engine.points()));
  sample(0);
  const auto started = std::chrono::steady_clock::now();
  for (std::int64_t n = 1; n <= cp.steps; ++n) {
    set_current_step(n);
    scheme.step_naming(cp.part(coupling::Solver::kMpm));
    probes.track(n, view_of(engine.points()));
    if (n % cp.sample_every == 0 || n == cp.steps) sample(n);
    if (grid_out && (n % cp.particles_every == 0 || n == cp.steps)) {
      write_grid(*grid_out, engine, n, static_cast<double>(n) * cp.time_step);
      write_points(*points_out, engine, n, static_cast<double>(n) * cp.time_step);
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  auto& r = ctx.results();
  if (grid_out) {
    r.files.push_back((std::filesystem::path(ctx.stage()) / "mpm_particles.h5md").string());
    r.files.push_back((std::filesystem::path(ctx.stage()) / "mpm_grid.h5").string());
    r.files.push_back((std::filesystem::path(ctx.stage()) / "mpm_grid.xdmf").string());
  }
  probes.report(r, "mpm");
  r.add_column("mpm_ledger", "stored_energy", "eV", stored);
  r.add_column("mpm_ledger", "dissipated_energy", "eV", dissipated);
  r.add_column("mpm_ledger", "mass", "g/mol", point_mass);
  coupling::report_exchanges(r, ctx.comm(), "mpm", link.nodal_profile(), link.partner_profile(),
                             cp.steps, seconds);
}

}  // namespace pbms::mpm
