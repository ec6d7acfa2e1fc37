#include "concurrent_mpm_part.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "engine_checkpoint.hpp"
#include "gas_probe.hpp"
#include "mpm_part_of_body.hpp"
#include "pbms/coupling/body_handover.hpp"
#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/coupling/concurrent_probes.hpp"
#include "pbms/coupling/conservation_ledger.hpp"
#include "pbms/coupling/coupling_scheme.hpp"
#include "pbms/coupling/cross_program_link.hpp"
#include "pbms/coupling/exchange_report.hpp"
#include "pbms/coupling/ghost_force_correction.hpp"
#include "pbms/coupling/scalar_across_programs.hpp"
#include "pbms/driver/stage_checkpoints.hpp"
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

// The MPM part's share of what the DPD part samples every sample_every
// steps (the probes, the tension curve's grip forces and stress, the
// interface opening), handed over in the order the DPD part asks for it.
class MpmPartSampler {
 public:
  MpmPartSampler(MPI_Comm comm, MPI_Comm inter, const coupling::ConcurrentParams& cp,
                 const MpmEngine& engine, coupling::ConcurrentProbes& probes)
      : comm_(comm), inter_(inter), cp_(cp), engine_(engine), probes_(probes) {}

  // Collective over both programs.
  void sample(std::int64_t n) {
    const auto v = view_of(engine_.points());
    probes_.sample(n, v);
    if (cp_.tension) hand_over_tension();
    if (cp_.opening) (void)coupling::swap_values(inter_, comm_, probes_.opening_moments(v));
  }

 private:
  void hand_over_tension() {
    const MpmModel& m = engine_.model();
    std::vector<std::uint32_t> masks;
    for (const auto& pv : m.bc.point_velocities) masks.push_back(pv.group_mask);
    const auto& reactions = engine_.solver().point_velocity_reactions();
    for (const auto& grip : {cp_.tension->left_grip, cp_.tension->right_grip}) {
      const double f =
          coupling::grip_force(comm_, reactions, masks, m.group_mask(grip), cp_.tension->axis);
      (void)coupling::swap_scalar(inter_, comm_, f);
    }
    // Σ σ V along the axis, bar Å^3 to eV.
    const grid::MaterialPoints& q = engine_.points();
    double sv = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      sv += q.volume(i) * q.state[i].stress.voigt[static_cast<std::size_t>(cp_.tension->axis)];
    }
    MPI_Allreduce(MPI_IN_PLACE, &sv, 1, MPI_DOUBLE, MPI_SUM, comm_);
    (void)coupling::swap_scalar(inter_, comm_, sv / units::kBarPerEvPerA3);
  }

  MPI_Comm comm_, inter_;
  const coupling::ConcurrentParams& cp_;
  const MpmEngine& engine_;
  coupling::ConcurrentProbes& probes_;
};

// The MPM part's points (H5MD) and its nodes (XDMF + HDF5), every
// particles_every steps.
class MpmPartOutput {
 public:
  // A resumed run (`resumed_after`, the checkpoint's step) goes on with the
  // files the interrupted one wrote, their later frames dropped.
  MpmPartOutput(StageContext& ctx, const coupling::ConcurrentParams& cp, const MpmEngine& engine,
                std::optional<std::int64_t> resumed_after) {
    H5mdWriter::Options o;
    o.path = (ctx.stage_dir() / "mpm_particles.h5md").string();
    o.creator_version = "mpm_driver (concurrent)";
    o.periodic = cp.periodic;
    o.velocities = true;
    const std::string grid = (ctx.stage_dir() / "mpm_grid").string();
    if (resumed_after) {
      points_ = H5mdWriter::reopen(ctx.comm(), o, engine.points().id, *resumed_after);
      grid_ =
          GridFieldWriter::reopen(ctx.comm(), grid, cp.grid, engine.owned_nodes(), *resumed_after);
      return;
    }
    points_ = std::make_unique<H5mdWriter>(ctx.comm(), o, engine.points().id,
                                           std::vector<int>(engine.points().size(), 1));
    write_points(*points_, engine, 0, 0.0);
    grid_ = std::make_unique<GridFieldWriter>(ctx.comm(), grid, cp.grid, engine.owned_nodes());
  }
  void write(const MpmEngine& engine, std::int64_t n, double t) {
    write_grid(*grid_, engine, n, t);
    write_points(*points_, engine, n, t);
  }
  static void list_files(StageResults& r, const std::string& stage) {
    r.files.push_back((std::filesystem::path(stage) / "mpm_particles.h5md").string());
    r.files.push_back((std::filesystem::path(stage) / "mpm_grid.h5").string());
    r.files.push_back((std::filesystem::path(stage) / "mpm_grid.xdmf").string());
  }

 private:
  std::unique_ptr<GridFieldWriter> grid_;
  std::unique_ptr<H5mdWriter> points_;
};

// The gas's points over the part's ranks.
std::int64_t count_gas_points(MPI_Comm comm, const MpmEngine& engine, int gas_material) {
  const auto& m = engine.points().material;
  std::int64_t n = std::count(m.begin(), m.end(), gas_material);
  MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_INT64_T, MPI_SUM, comm);
  return n;
}

// A ledger row of the MPM part at step n: its motion and its stored and
// dissipated energy.
void add_to_ledger(coupling::ConservationLedger& ledger, const MpmEngine& engine, std::int64_t n,
                   double dt, const GasProbe* gas) {
  auto row = ledger.motion_of(static_cast<double>(n) * dt, view_of(engine.points()));
  if (gas != nullptr) row.wall_impulse = gas->wall_impulse();
  const grid::EnergySummary energy = engine.solver().energy(engine.points());
  row.energies = {energy.stored, energy.dissipated};
  ledger.add(std::move(row));
}

// Everything the MPM part needs to go on after a step as if never stopped:
// the engine's points, the held groups' velocities, and what it has
// measured so far.
struct MpmPartCheckpoint {
  MpmEngine& engine;
  coupling::ConcurrentProbes& probes;
  coupling::ConservationLedger& ledger;
  GasProbe* gas;
  coupling::GhostForceCorrection* ghost_forces;

  // Collective over the part's ranks.
  [[nodiscard]] CheckpointArchive save() const {
    CheckpointArchive a;
    put_engine_state(a, engine);
    probes.save(a);
    ledger.save(a);
    if (gas != nullptr) gas->save(a);
    if (ghost_forces != nullptr) ghost_forces->save(a);
    return a;
  }
  // Returns the step the archive was written after.
  std::int64_t load(const CheckpointArchive& a) {
    const std::int64_t step = take_engine_state(a, engine);
    probes.load(a);
    (void)ledger.load(a);  // this part adds its rows as it goes: none pending
    if (gas != nullptr) gas->load(a);
    if (ghost_forces != nullptr) ghost_forces->load(a);
    return step;
  }
};

// Where a stage leaves its ghost forces' dead loads for later stages.
constexpr const char* kGhostForceFile = "ghost_forces.h5";

// What the ghost-force correction subtracts: on how many points, the
// largest on one, and the largest net a part's measured mean held (which
// the correction leaves out).
void report_ghost_forces(StageResults& r, const coupling::GhostForceCorrection& g) {
  r.add_scalar("ghost_force_points", static_cast<double>(g.points()), "1");
  r.add_scalar("ghost_force_largest", g.largest(), "eV/Å");
  r.add_scalar("ghost_force_net_removed", g.net_removed(), "eV/Å");
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
  int remote = 0;
  MPI_Comm_remote_size(inter, &remote);
  const grid::GridPartition theirs(cp.grid, cp.periodic, remote);
  coupling::CrossProgramLink link(inter, part.side(), engine.partition(), theirs, part.band(),
                                  part.reach());
  coupling::CouplingScheme scheme({&part.side()}, link, cp.interface, cp.fields(), cp.move);

  coupling::ConcurrentProbes probes(ctx.comm(), cp, part.group_names(),
                                    0.5 * part.lattice_constant(), view_of(engine.points()));
  // The part's mass (the gas's included: the momentum is everything's).
  const auto& masses = engine.points().mass;
  double mass = std::accumulate(masses.begin(), masses.end(), 0.0);
  MPI_Allreduce(MPI_IN_PLACE, &mass, 1, MPI_DOUBLE, MPI_SUM, ctx.comm());
  (void)coupling::swap_scalar(inter, ctx.comm(), mass);
  coupling::ConservationLedger ledger(ctx.comm(), {"stored_energy", "dissipated_energy"},
                                      cp.gas && cp.gas->walls);
  std::optional<GasProbe> gas;
  if (cp.gas) {
    gas.emplace(ctx.comm(), *cp.gas, part.gas_material(),
                engine.model().group_mask(MpmPartOfBody::kGasAwayGroup));
  }
  GasProbe* gas_probe = gas ? &*gas : nullptr;
  std::optional<coupling::GhostForceCorrection> ghost_forces;
  if (!cp.ghost_force_stage.empty()) {
    ghost_forces.emplace(coupling::GhostForceCorrection::read(
        ctx.comm(), ctx.run_dir() / cp.ghost_force_stage / kGhostForceFile));
  } else if (cp.ghost_force_steps > 0) {
    ghost_forces.emplace(ctx.comm(), cp.ghost_force_steps);
  }
  if (ghost_forces) {
    part.side().correct_ghost_forces(*ghost_forces,
                                     [&cp](const grid::Vec3& x) { return cp.region_at(x); });
  }
  MpmPartSampler sampler(ctx.comm(), inter, cp, engine, probes);
  // The checkpoints dpd_driver's part writes, at the same steps (a step
  // after one chooses the partners afresh, as a resumed run's first does).
  StageCheckpoints checkpoints(ctx);
  checkpoints.run_as_part(
      "mpm", [&](bool mine) { return coupling::either_program(inter, ctx.comm(), mine); });
  MpmPartCheckpoint state{engine, probes, ledger, gas_probe,
                          ghost_forces ? &*ghost_forces : nullptr};
  std::unique_ptr<MpmPartOutput> output;
  std::int64_t first_step = 1;
  if (checkpoints.enabled() && checkpoints.resuming()) {
    first_step = state.load(checkpoints.resume_archive()) + 1;
    if (cp.particles_every > 0) {
      output = std::make_unique<MpmPartOutput>(ctx, cp, engine, first_step - 1);
    }
  } else {
    if (cp.particles_every > 0) {
      output = std::make_unique<MpmPartOutput>(ctx, cp, engine, std::nullopt);
    }
    probes.track(0, view_of(engine.points()));
    add_to_ledger(ledger, engine, 0, cp.time_step, gas_probe);
    sampler.sample(0);
    if (gas) gas->sample(0.0, engine);
  }
  const auto started = std::chrono::steady_clock::now();
  for (std::int64_t n = first_step; n <= cp.steps; ++n) {
    set_current_step(n);
    part.ramp_grips(n);
    scheme.step_naming(cp.part(coupling::Solver::kMpm));
    part.hold_gas_temperature(n);
    probes.track(n, view_of(engine.points()));
    const double t = static_cast<double>(n) * cp.time_step;
    if (gas) gas->after_step(engine);
    add_to_ledger(ledger, engine, n, cp.time_step, gas_probe);
    if (n % cp.sample_every == 0 || n == cp.steps) {
      sampler.sample(n);
      if (gas) gas->sample(t, engine);
    }
    if (output && (n % cp.particles_every == 0 || n == cp.steps)) output->write(engine, n, t);
    const bool stop = checkpoints.stop_agreed(n) && n < cp.steps;
    if (stop || checkpoints.due(n, cp.steps)) {
      const std::string file = checkpoints.write(n, t, [&] { return state.save(); });
      part.side().forget_followed_points();
      if (stop) throw StageFailure(StageCheckpoints::stopped_message(n, cp.steps, file));
    }
  }
  // Exchange figures are of the steps this run made.
  const std::int64_t steps_run = cp.steps - first_step + 1;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  // The stepping's exchanges, without the closing pass's.
  const coupling::ExchangeProfile nodal = link.nodal_profile(), partners = link.partner_profile();
  scheme.close();
  (void)ledger.momentum_drift(inter);  // dpd_driver reports it
  auto& r = ctx.results();
  checkpoints.report(r);
  if (output) MpmPartOutput::list_files(r, ctx.stage());
  probes.report(r, "mpm");
  ledger.report(r, "mpm");
  if (gas) gas->report(r, count_gas_points(ctx.comm(), engine, part.gas_material()));
  if (ghost_forces) {
    report_ghost_forces(r, *ghost_forces);
    ghost_forces->write(ctx.stage_dir() / kGhostForceFile);
    r.files.push_back((std::filesystem::path(ctx.stage()) / kGhostForceFile).string());
  }
  // With no point of its own (a body all DPD) this part only answered
  // dpd_driver's exchanges; figures for it would describe nothing.
  if (engine.total_points() > 0) {
    coupling::report_exchanges(r, ctx.comm(), "mpm", nodal, partners, steps_run, seconds);
  } else {
    r.attributes["mpm_exchange_note"] =
        "the body holds no MPM point: mpm_driver only answered dpd_driver's exchanges, and its "
        "exchange figures are left out";
  }
}

}  // namespace pbms::mpm
