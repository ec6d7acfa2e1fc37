#include "concurrent_mpm_part.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "mpm_part_of_body.hpp"
#include "pbms/coupling/body_handover.hpp"
#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/coupling/concurrent_probes.hpp"
#include "pbms/coupling/conservation_ledger.hpp"
#include "pbms/coupling/coupling_scheme.hpp"
#include "pbms/coupling/cross_program_link.hpp"
#include "pbms/coupling/exchange_report.hpp"
#include "pbms/coupling/scalar_across_programs.hpp"
#include "pbms/error.hpp"
#include "pbms/grid/for_each_node.hpp"
#include "pbms/grid/grid_field_writer.hpp"
#include "pbms/io/h5md_writer.hpp"
#include "pbms/units.hpp"

namespace pbms::mpm {
namespace {

// The nodes this rank writes: mass and velocity as the MPM part holds them
// after a step, both parts' sums on the interface band's nodes.
void write_grid(GridFieldWriter& out, const MpmEngine& engine, std::int64_t step, double t) {
  const grid::MpmSolver& solver = engine.solver();
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
  const grid::MaterialPoints& p = engine.points();
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

coupling::ParticleView view_of(const grid::MaterialPoints& p) {
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
  const coupling::ConcurrentParams cp =
      coupling::ConcurrentParams::from_yaml(ctx.params(), ctx.material());
  const MPI_Comm inter = ctx.peer("dpd_driver");
  if (inter == MPI_COMM_NULL) {
    throw Error(fmt::format("stage '{}': dpd_driver is not running", ctx.stage()));
  }
  MpmPartOfBody part(ctx.comm(), cp, coupling::take_over(inter, ctx.comm()));
  MpmEngine& engine = part.engine();
  const auto& groups = part.group_names();
  const double a = part.lattice_constant();
  int remote = 0;
  MPI_Comm_remote_size(inter, &remote);
  const grid::GridPartition theirs(cp.grid, cp.periodic, remote);
  coupling::CrossProgramLink link(inter, part.side(), engine.partition(), theirs, part.band(),
                                  part.reach());
  coupling::CouplingScheme scheme({&part.side()}, link, cp.interface);

  coupling::ConcurrentProbes probes(ctx.comm(), cp, groups, 0.5 * a, view_of(engine.points()));
  const double mass = static_cast<double>(engine.total_points()) * cp.particle_mass;
  (void)coupling::swap_scalar(inter, ctx.comm(), mass);
  coupling::ConservationLedger ledger(ctx.comm(), {"stored_energy", "dissipated_energy"});
  auto add_to_ledger = [&](std::int64_t n) {
    auto row = ledger.motion_of(static_cast<double>(n) * cp.time_step, view_of(engine.points()));
    const grid::EnergySummary energy = engine.solver().energy(engine.points());
    row.energies = {energy.stored, energy.dissipated};
    ledger.add(std::move(row));
  };
  auto sample = [&](std::int64_t n) {
    const auto v = view_of(engine.points());
    probes.sample(n, v);
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
      const grid::MaterialPoints& q = engine.points();
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
  add_to_ledger(0);
  sample(0);
  const auto started = std::chrono::steady_clock::now();
  for (std::int64_t n = 1; n <= cp.steps; ++n) {
    set_current_step(n);
    part.ramp_grips(n);
    scheme.step_naming(cp.part(coupling::Solver::kMpm));
    probes.track(n, view_of(engine.points()));
    add_to_ledger(n);
    if (n % cp.sample_every == 0 || n == cp.steps) sample(n);
    if (grid_out && (n % cp.particles_every == 0 || n == cp.steps)) {
      write_grid(*grid_out, engine, n, static_cast<double>(n) * cp.time_step);
      write_points(*points_out, engine, n, static_cast<double>(n) * cp.time_step);
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  // The stepping's exchanges, without the closing pass's.
  const coupling::ExchangeProfile nodal = link.nodal_profile(), partners = link.partner_profile();
  scheme.close();
  (void)ledger.momentum_drift(inter);  // dpd_driver reports it
  auto& r = ctx.results();
  if (grid_out) {
    r.files.push_back((std::filesystem::path(ctx.stage()) / "mpm_particles.h5md").string());
    r.files.push_back((std::filesystem::path(ctx.stage()) / "mpm_grid.h5").string());
    r.files.push_back((std::filesystem::path(ctx.stage()) / "mpm_grid.xdmf").string());
  }
  probes.report(r, "mpm");
  ledger.report(r, "mpm");
  coupling::report_exchanges(r, ctx.comm(), "mpm", nodal, partners, cp.steps, seconds);
}

}  // namespace pbms::mpm
