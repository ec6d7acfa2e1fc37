#include "concurrent_stage.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numeric>
#include <optional>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "block_volume_probe.hpp"
#include "dpd_model.hpp"
#include "dpd_part_of_body.hpp"
#include "dpd_particle_view.hpp"
#include "dpd_run.hpp"
#include "dpd_stage_params.hpp"
#include "engine/dpd_engine.hpp"
#include "engine/dpd_grid_step.hpp"
#include "engine_checkpoint.hpp"
#include "neck_probe.hpp"
#include "pbms/analysis/quasi_static_pull.hpp"
#include "pbms/coupling/body_handover.hpp"
#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/coupling/concurrent_probes.hpp"
#include "pbms/coupling/concurrent_spec.hpp"
#include "pbms/coupling/conservation_ledger.hpp"
#include "pbms/coupling/coupling_scheme.hpp"
#include "pbms/coupling/cross_program_link.hpp"
#include "pbms/coupling/exchange_report.hpp"
#include "pbms/coupling/scalar_across_programs.hpp"
#include "pbms/driver/stage_checkpoints.hpp"
#include "pbms/error.hpp"
#include "pbms/io/h5md_writer.hpp"
#include "pbms/units.hpp"
#include "pbms/velocity_ramp.hpp"
#include "rod_probe.hpp"

namespace pbms::dpd {
namespace {

// Grip stress against strain, both grips held at their velocities.
struct TensionSeries {
  coupling::TensionProbe probe;
  std::uint32_t left = 0, right = 0;
  // Each grip's full speed along the axis (Å/ps, the left one's counted
  // negative) and its ramp time (ps).
  std::vector<std::pair<double, double>> grips;
  double length = 0.0, area = 0.0, width = 0.0;
  double density = 0.0;                                   // g/mol/Å^3 of the body's crystal
  std::vector<double> time, strain, stress, grip_stress;  // ps, 1, GPa, GPa

  TensionSeries(const coupling::TensionProbe& t, const DpdPartOfBody& part)
      : probe(t), left(part.group_mask(t.left_grip)), right(part.group_mask(t.right_grip)) {
    const double a0 = part.params().point_lattice_constant();
    density = 4.0 * part.params().particle_mass / (a0 * a0 * a0);
    const auto a = static_cast<std::size_t>(t.axis);
    for (const auto& g : part.group_motions()) {
      if (g.mask == left) grips.emplace_back(-g.velocity[a], g.ramp_time);
      if (g.mask == right) grips.emplace_back(g.velocity[a], g.ramp_time);
    }
    length = part.body_extent()[a];
    // The nominal cross-section: the sites' volume over the length. The
    // outermost sites' thermal excursions and the surfaces' relaxation
    // widen the extents across the rod by 0.8-0.9 Å at 298 K, 4 % on a
    // 6 x 6 a_cg section; that area would read the rod 4 % soft, and an
    // MPM part given that E 4 % softer again (docs/concurrent.md).
    area = part.nominal_volume() / length;
    for (std::size_t b = 0; b < 3; ++b) {
      if (b != a) width = std::max(width, part.body_extent()[b]);
    }
  }
  // The body's mean axial stress from the DPD part's conservative virial
  // and the MPM part's sum of stress times volume (both eV), over the
  // nominal cross-section times the current length, as dpd_run's tension
  // measures it; and the grips' holding forces (each part's plus the
  // other's) over the nominal cross-section.
  void add(double t, double dpd_virial, double mpm_stress_volume, double f_left, double f_right) {
    double separation = 0.0;  // the grips' change of distance since the start
    for (const auto& [speed, ramp] : grips) separation += speed * ramp_displacement(t, ramp);
    const double e = separation / length;
    constexpr double kGPa = units::kBarPerEvPerA3 / units::kBarPerGPa;  // eV/Å^3 to GPa
    time.push_back(t);
    strain.push_back(e);
    stress.push_back((mpm_stress_volume - dpd_virial) / (area * length * (1.0 + e)) * kGPa);
    grip_stress.push_back(0.5 * (f_right - f_left) / area * kGPa);
  }
  void report(StageResults& r) const {
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (std::size_t k = 0; k < strain.size(); ++k) {
      if (strain[k] > probe.fit_strain) continue;
      sx += strain[k];
      sy += stress[k];
      sxx += strain[k] * strain[k];
      sxy += strain[k] * stress[k];
      n += 1;
    }
    r.add_column("tension_curve", "strain", "1", strain);
    r.add_column("tension_curve", "stress", "GPa", stress);
    r.add_column("tension_curve", "grip_stress", "GPa", grip_stress);
    if (n >= 3) {
      r.add_scalar("youngs_modulus", (n * sxy - sx * sy) / (n * sxx - sx * sx), "GPa");
      analysis::check_quasi_static(r, density, width,
                                   analysis::fit_window_time(strain, time, probe.fit_strain));
    }
    if (!stress.empty()) {
      r.add_scalar("max_stress", *std::max_element(stress.begin(), stress.end()), "GPa");
    }
  }
  void save(CheckpointArchive& a) const {
    a.put("tension/time", time);
    a.put("tension/strain", strain);
    a.put("tension/stress", stress);
    a.put("tension/grip_stress", grip_stress);
  }
  void load(const CheckpointArchive& a) {
    time = a.get("tension/time");
    strain = a.get("tension/strain");
    stress = a.get("tension/stress");
    grip_stress = a.get("tension/grip_stress");
  }
};

std::vector<std::uint32_t> motion_masks(const DpdPartOfBody& part) {
  std::vector<std::uint32_t> out;
  for (const auto& g : part.group_motions()) out.push_back(g.mask);
  return out;
}

// The DPD part's particles, one H5MD frame, each rank writing its own.
class DpdPartTrajectory {
 public:
  // A resumed run (`resumed_after`, the checkpoint's step) goes on with the
  // file the interrupted one wrote, its later frames dropped.
  DpdPartTrajectory(const DpdEngine& e, const std::filesystem::path& path,
                    std::optional<std::int64_t> resumed_after = std::nullopt) {
    H5mdWriter::Options o;
    o.path = path.string();
    o.creator_version = "dpd_driver (concurrent)";
    o.periodic = e.domain().box().periodic;
    o.velocities = true;
    const DpdParticles& p = e.particles();
    const std::vector<std::int64_t> ids(p.id.begin(), p.id.begin() + static_cast<long>(e.owned()));
    const std::vector<int> types(p.type.begin(), p.type.begin() + static_cast<long>(e.owned()));
    writer_ = resumed_after ? H5mdWriter::reopen(e.comm(), o, ids, *resumed_after)
                            : std::make_unique<H5mdWriter>(e.comm(), o, ids, types);
    const OrthogonalBox& box = e.domain().box();
    for (int a = 0; a < 3; ++a) edges_[static_cast<std::size_t>(a)] = box.length(a);
  }
  void write(const DpdEngine& e, std::int64_t step, double t) {
    const DpdParticles& p = e.particles();
    std::vector<std::int64_t> ids;
    std::vector<double> x, v;
    for (std::size_t i = 0; i < e.owned(); ++i) {
      ids.push_back(p.id[i]);
      x.insert(x.end(), p.x[i].begin(), p.x[i].end());
      v.insert(v.end(), p.v[i].begin(), p.v[i].end());
    }
    writer_->write_frame(step, t, edges_, ids, x, v);
  }

 private:
  std::unique_ptr<H5mdWriter> writer_;
  std::array<double, 3> edges_{};
};

// The DPD part's conservation ledger. A row's pair energies are tallied by
// the force pass after it (the next step's, or the scheme's close), the
// first one at the row's positions and with the partners there.
class DpdLedger {
 public:
  explicit DpdLedger(MPI_Comm comm)
      : ledger_(comm, {"potential_energy", "interface_pair_energy", "internal_energy"}) {}
  void motion(double t, const coupling::ParticleView& now, const DpdEngine& e) {
    pending_ = ledger_.motion_of(t, now);
    const auto& u = e.particles().internal_energy;
    pending_.energies[2] =
        std::accumulate(u.begin(), u.begin() + static_cast<long>(e.owned()), 0.0);
  }
  // Collective over the part's ranks.
  void energies(const DpdEngine& e) {
    const PairResult& tally = e.last_tally();
    pending_.energies[0] = tally.energy - tally.partner_energy;
    pending_.energies[1] = tally.partner_energy;
    ledger_.add(pending_);
  }
  [[nodiscard]] const coupling::ConservationLedger& table() const { return ledger_; }
  // Collective: the rows, and the pending one whose energies the next
  // force pass tallies.
  void save(CheckpointArchive& a) const { ledger_.save(a, &pending_); }
  void load(const CheckpointArchive& a) { pending_ = ledger_.load(a); }

 private:
  coupling::ConservationLedger ledger_;
  coupling::ConservationLedger::Row pending_;
};

// The planes' displacement jump since the start: at the end, its largest
// opening (the planes apart) and its largest closing (the planes nearer,
// which the compressive front does to any two planes, interface or not).
void report_opening(StageResults& r, const std::vector<double>& t,
                    const std::vector<double>& jump) {
  r.add_column("interface", "time", "ps", t);
  r.add_column("interface", "opening", "Å", jump);
  double apart = 0.0, nearer = 0.0;
  for (const double o : jump) {
    apart = std::max(apart, o - jump.front());
    nearer = std::max(nearer, jump.front() - o);
  }
  r.add_scalar("interface_opening", jump.back() - jump.front(), "Å");
  r.add_scalar("max_interface_opening", apart, "Å");
  r.add_scalar("max_interface_closing", nearer, "Å");
}

// What the DPD part samples every sample_every steps: the probes, the
// tension curve and the interface opening, each its share summed with
// mpm_driver's (whose part makes the same calls in the same order).
class DpdPartSampler {
 public:
  DpdPartSampler(MPI_Comm comm, MPI_Comm inter, DpdPartOfBody& part, DpdView& view,
                 coupling::ConcurrentProbes& probes)
      : comm_(comm), inter_(inter), part_(part), cp_(part.params()), view_(view), probes_(probes) {
    if (cp_.tension) tension_.emplace(*cp_.tension, part);
    if (cp_.volume) {
      volume_.emplace(comm, *cp_.volume, part.group_mask(cp_.volume->group),
                      cp_.material_lattice_constant, view.view(part.engine()));
    }
    for (const auto& n : cp_.necks) {
      necks_.emplace_back(comm, n, part.group_mask(n.first), part.group_mask(n.second),
                          cp_.material_lattice_constant);
    }
    for (const auto& rod : cp_.rods) {
      rods_.emplace_back(comm, rod, part.group_mask(rod.group), cp_.material_lattice_constant,
                         view.view(part.engine()));
    }
  }

  // Collective over both programs.
  void sample(std::int64_t n) {
    DpdEngine& engine = part_.engine();
    const auto v = view_.view(engine);
    probes_.sample(n, v);
    if (tension_) sample_tension(n);
    if (volume_) volume_->sample(static_cast<double>(n) * cp_.time_step, v);
    for (auto& neck : necks_) neck.sample(static_cast<double>(n) * cp_.time_step, v);
    for (auto& rod : rods_) rod.sample(static_cast<double>(n) * cp_.time_step, v);
    if (cp_.opening) {
      const auto mine = probes_.opening_moments(v);
      opening_t_.push_back(static_cast<double>(n) * cp_.time_step);
      opening_.push_back(
          coupling::ConcurrentProbes::opening(mine, coupling::swap_values(inter_, comm_, mine)));
    }
  }

  void report(StageResults& r) const {
    if (cp_.opening && !opening_.empty()) report_opening(r, opening_t_, opening_);
    if (volume_) volume_->report(r);
    for (const auto& neck : necks_) neck.report(r, cp_.neck_stable_time);
    for (const auto& rod : rods_) rod.report(r);
  }
  void report_tension(StageResults& r) const {
    if (tension_) tension_->report(r);
  }
  void save(CheckpointArchive& a) const {
    if (tension_) tension_->save(a);
    if (volume_) volume_->save(a);
    for (const auto& neck : necks_) neck.save(a);
    for (const auto& rod : rods_) rod.save(a);
    a.put("opening/time", opening_t_);
    a.put("opening/value", opening_);
  }
  void load(const CheckpointArchive& a) {
    if (tension_) tension_->load(a);
    if (volume_) volume_->load(a);
    for (auto& neck : necks_) neck.load(a);
    for (auto& rod : rods_) rod.load(a);
    opening_t_ = a.get("opening/time");
    opening_ = a.get("opening/value");
  }

 private:
  void sample_tension(std::int64_t n) {
    const auto& reactions = part_.grid().solver().point_velocity_reactions();
    const auto masks = motion_masks(part_);
    const int a = tension_->probe.axis;
    double f[2] = {coupling::grip_force(comm_, reactions, masks, tension_->left, a),
                   coupling::grip_force(comm_, reactions, masks, tension_->right, a)};
    for (double& x : f) x += coupling::swap_scalar(inter_, comm_, x);
    const double w =
        part_.engine().thermo(true).virial[static_cast<std::size_t>(a)];  // a pair pass
    const double sv = coupling::swap_scalar(inter_, comm_, 0.0);
    tension_->add(static_cast<double>(n) * cp_.time_step, w, sv, f[0], f[1]);
  }

  MPI_Comm comm_, inter_;
  DpdPartOfBody& part_;
  const coupling::ConcurrentParams& cp_;
  DpdView& view_;
  coupling::ConcurrentProbes& probes_;
  std::optional<TensionSeries> tension_;
  std::optional<BlockVolumeProbe> volume_;
  std::vector<NeckProbe> necks_;
  std::vector<RodProbe> rods_;
  std::vector<double> opening_t_, opening_;
};

// The whole body's mass: this part's and mpm_driver's (collective over both).
double body_mass(MPI_Comm comm, MPI_Comm inter, DpdPartOfBody& part) {
  const double mine = part.dpd_particles() * part.engine().particles().mass_per_type[0];
  return coupling::swap_scalar(inter, comm, mine) + mine;
}

// The speed momentum changes are reported against (M c), Å/ps (bar
// Å³/(g/mol) to Å²/ps²): the bar speed sqrt(E / rho) of the MPM points'
// material, or without one the gas's sound speed sqrt(gamma P / rho).
double bar_speed(const coupling::ConcurrentParams& cp) {
  const double a = cp.point_lattice_constant();
  const double rho = 4.0 * cp.particle_mass / (a * a * a);
  constexpr double kToA2PerPs2 = 1.0 / units::kBarPerEvPerA3 / units::kMvv2e;
  if (cp.youngs_modulus > 0.0) return std::sqrt(cp.youngs_modulus / rho * kToA2PerPs2);
  if (cp.gas && cp.gas->pressure > 0.0) {
    return std::sqrt(cp.gas->gamma * cp.gas->pressure / cp.gas->density * kToA2PerPs2);
  }
  return 1.0;
}

// Bytes the DPD part's ranks sent in the nodal sums and received as
// partners, per step, summed over its ranks.
void report_bytes(StageResults& r, MPI_Comm comm, const coupling::ExchangeProfile& nodal,
                  const coupling::ExchangeProfile& partners, std::int64_t steps) {
  double bytes[2] = {static_cast<double>(nodal.bytes_sent),
                     static_cast<double>(partners.bytes_received)};
  MPI_Allreduce(MPI_IN_PLACE, bytes, 2, MPI_DOUBLE, MPI_SUM, comm);
  const double n = std::max<double>(1.0, static_cast<double>(steps));
  r.add_scalar("nodal_sum_bytes_per_step", bytes[0] / n, "1");
  r.add_scalar("partner_bytes_per_step", bytes[1] / n, "1");
}

// Everything the DPD part needs to go on after a step as if never stopped:
// the engine's particles, the rigid groups' velocities, and what it has
// measured so far.
struct DpdPartCheckpoint {
  DpdPartOfBody& part;
  coupling::ConcurrentProbes& probes;
  DpdPartSampler& sampler;
  DpdLedger& ledger;

  // Collective over the part's ranks.
  [[nodiscard]] CheckpointArchive save() const {
    CheckpointArchive a;
    put_engine_state(a, part.engine(), &part.grid());
    probes.save(a);
    sampler.save(a);
    ledger.save(a);
    return a;
  }
  // Returns the step the archive was written after.
  std::int64_t load(const CheckpointArchive& a) {
    const std::int64_t step = take_engine_state(a, part.engine(), &part.grid());
    probes.load(a);
    sampler.load(a);
    ledger.load(a);
    return step;
  }
};

}  // namespace

config::StageKindSpec ConcurrentStage::spec() {
  return coupling::concurrent_spec(dpd_stage_params());
}

void ConcurrentStage::run(StageContext& ctx) {
  const MPI_Comm inter = ctx.peer("mpm_driver");
  if (inter == MPI_COMM_NULL) {
    throw Error(fmt::format("stage '{}': mpm_driver is not running", ctx.stage()));
  }
  use_run_directory(ctx.run_dir());
  DpdPartOfBody part(ctx.comm(), ctx.params(), ctx.material(), ctx.seed(), ctx.stage());
  const coupling::ConcurrentParams& cp = part.params();
  coupling::hand_over(inter, ctx.comm(), part.handover());
  DpdEngine& engine = part.engine();
  DpdGridStep& grid = part.grid();
  int remote = 0;
  MPI_Comm_remote_size(inter, &remote);
  const grid::GridPartition theirs(cp.grid, cp.periodic, remote);
  coupling::CrossProgramLink link(inter, part.side(), grid.partition(), theirs, part.band(),
                                  part.reach());
  coupling::CouplingScheme scheme({&part.side()}, link, cp.interface, cp.fields(), cp.move);

  DpdView view;
  coupling::ConcurrentProbes probes(ctx.comm(), cp, part.group_names(),
                                    0.5 * cp.material_lattice_constant, view.view(engine));
  const double mass = body_mass(ctx.comm(), inter, part);
  DpdPartSampler sampler(ctx.comm(), inter, part, view, probes);
  DpdLedger ledger(ctx.comm());
  grid.tally_each_step(true);
  // Both parts write a checkpoint at the same steps; a step after one
  // chooses the partners afresh (concurrent_mpm_part), as a resumed run's
  // first step does.
  StageCheckpoints checkpoints(ctx);
  checkpoints.run_as_part(
      "", [&](bool mine) { return coupling::either_program(inter, ctx.comm(), mine); });
  DpdPartCheckpoint state{part, probes, sampler, ledger};
  const std::filesystem::path particles_file = ctx.stage_dir() / "dpd_particles.h5md";
  std::unique_ptr<DpdPartTrajectory> trajectory;
  std::int64_t first_step = 1;
  if (checkpoints.enabled() && checkpoints.resuming()) {
    first_step = state.load(checkpoints.resume_archive()) + 1;
    if (cp.particles_every > 0) {
      trajectory = std::make_unique<DpdPartTrajectory>(engine, particles_file, first_step - 1);
    }
  } else {
    if (cp.particles_every > 0) {
      trajectory = std::make_unique<DpdPartTrajectory>(engine, particles_file);
      trajectory->write(engine, 0, 0.0);
    }
    probes.track(0, view.view(engine));
    ledger.motion(0.0, view.view(engine), engine);
    sampler.sample(0);
  }
  const auto started = std::chrono::steady_clock::now();
  for (std::int64_t n = first_step; n <= cp.steps; ++n) {
    set_current_step(n);
    part.ramp_grips(n);
    scheme.step_naming(cp.part(coupling::Solver::kDpd));
    if (cp.thermostat) engine.berendsen(cp.thermostat->first, cp.thermostat->second, true);
    ledger.energies(engine);
    const auto now = view.view(engine);
    const double t = static_cast<double>(n) * cp.time_step;
    ledger.motion(t, now, engine);
    probes.track(n, now);
    if (n % cp.sample_every == 0 || n == cp.steps) sampler.sample(n);
    if (trajectory && (n % cp.particles_every == 0 || n == cp.steps))
      trajectory->write(engine, n, t);
    const bool stop = checkpoints.stop_agreed(n) && n < cp.steps;
    if (stop || checkpoints.due(n, cp.steps)) {
      const std::string file = checkpoints.write(n, t, [&] { return state.save(); });
      if (stop) throw StageFailure(StageCheckpoints::stopped_message(n, cp.steps, file));
    }
    ctx.progress(n, cp.steps, t, "concurrent");
  }
  // Rates and exchange figures are of the steps this run made.
  const std::int64_t steps_run = cp.steps - first_step + 1;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  // The stepping's exchanges, without the closing pass's.
  const coupling::ExchangeProfile nodal = link.nodal_profile(), partners = link.partner_profile();
  scheme.close();
  ledger.energies(engine);

  auto& r = ctx.results();
  checkpoints.report(r);
  if (trajectory)
    r.files.push_back((std::filesystem::path(ctx.stage()) / "dpd_particles.h5md").string());
  r.attributes["interface"] = cp.interface_name;
  r.add_scalar("dpd_particles", part.dpd_particles(), "1");
  r.add_scalar("mpm_points", part.mpm_points(), "1");
  r.add_scalar("dpd_temperature", engine.thermo(false).temperature, "K");
  r.add_scalar("momentum_change", ledger.table().momentum_drift(inter) / (mass * bar_speed(cp)),
               "1");
  sampler.report(r);
  if (steps_run > 0 && seconds > 0.0) {
    r.add_scalar("steps_per_second", static_cast<double>(steps_run) / seconds, "1/s");
  }
  probes.report(r, "dpd");
  ledger.table().report(r, "dpd");
  sampler.report_tension(r);
  // With no particle of its own (a body all MPM) this part only answered
  // mpm_driver's exchanges; figures for it would describe nothing.
  if (part.dpd_particles() > 0) {
    coupling::report_exchanges(r, ctx.comm(), "dpd", nodal, partners, steps_run, seconds);
    report_bytes(r, ctx.comm(), nodal, partners, steps_run);
  } else {
    r.attributes["dpd_exchange_note"] =
        "the body holds no DPD particle: dpd_driver only answered mpm_driver's exchanges, and "
        "its exchange figures are left out";
  }
}

}  // namespace pbms::dpd
