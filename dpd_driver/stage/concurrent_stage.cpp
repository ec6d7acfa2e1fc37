#include "concurrent_stage.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "dpd_model.hpp"
#include "engine/concurrent_dpd_side.hpp"
#include "engine/dpd_engine.hpp"
#include "engine/dpd_grid_step.hpp"
#include "kernels/periodic_wrap.hpp"
#include "pbms/coupling/body_handover.hpp"
#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/coupling/concurrent_probes.hpp"
#include "pbms/coupling/coupling_scheme.hpp"
#include "pbms/coupling/cross_program_link.hpp"
#include "pbms/coupling/exchange_report.hpp"
#include "pbms/coupling/scalar_across_programs.hpp"
#include "pbms/error.hpp"
#include "pbms/io/h5md_writer.hpp"
#include "pbms/units.hpp"

namespace pbms::dpd {
namespace {

using coupling::ConcurrentParams;
using coupling::Solver;

// id, x, v, mass, group bits: what mpm_driver gets of each of its points.
constexpr std::size_t kRowWidth = 9;

struct SplitBody {
  DpdParticles dpd;
  std::vector<double> mpm_rows;
};

SplitBody split_body(const DpdParticles& all, const ConcurrentParams& cp) {
  SplitBody s;
  s.dpd.mass_per_type = all.mass_per_type;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (cp.solver_at(all.x[i]) == Solver::kMpm) {
      s.mpm_rows.insert(s.mpm_rows.end(), {static_cast<double>(all.id[i]), all.x[i][0], all.x[i][1],
                                           all.x[i][2], all.v[i][0], all.v[i][1], all.v[i][2],
                                           all.mass(i), static_cast<double>(all.group_mask[i])});
      continue;
    }
    s.dpd.add(all.id[i], all.type[i], all.x[i], all.v[i]);
    s.dpd.image.back() = all.image[i];
    s.dpd.internal_energy.back() = all.internal_energy[i];
    s.dpd.group_mask.back() = all.group_mask[i];
  }
  return s;
}

// The cells a set of positions touches, grown by `margin`, as nodes.
grid::NodeBox nodes_around(const std::vector<Vec3>& x, const grid::RegularGrid& g, double margin) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  for (const auto& p : x) {
    for (std::size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  grid::NodeBox b;
  if (x.empty()) return b;
  for (std::size_t a = 0; a < 3; ++a) {
    b.lo[a] = static_cast<int>(std::floor((lo[a] - margin - g.origin()[a]) / g.cell_size()));
    b.hi[a] = static_cast<int>(std::floor((hi[a] + margin - g.origin()[a]) / g.cell_size())) + 2;
  }
  return b.intersected(g.node_box());
}

// The nodes both parts may deposit on. On periodic axes the whole axis:
// the plan folds images onto their owners.
grid::NodeBox interface_band(const SplitBody& body, const ConcurrentParams& cp, double reach) {
  std::vector<Vec3> mpm;
  for (std::size_t r = 0; r < body.mpm_rows.size(); r += kRowWidth) {
    mpm.push_back({body.mpm_rows[r + 1], body.mpm_rows[r + 2], body.mpm_rows[r + 3]});
  }
  const double margin = cp.band_margin + reach;
  grid::NodeBox band =
      nodes_around(body.dpd.x, cp.grid, margin).intersected(nodes_around(mpm, cp.grid, margin));
  for (std::size_t a = 0; a < 3; ++a) {
    if (cp.periodic[a] && !band.empty()) {
      band.lo[a] = 0;
      band.hi[a] = cp.grid.cells()[a] + 1;
    }
  }
  return band;
}

std::string header_yaml(const std::vector<std::string>& group_names, const grid::NodeBox& band,
                        double reach, double skin) {
  YAML::Node h;
  h["groups"] = group_names;
  h["band_lo"] = std::vector<int>(band.lo.begin(), band.lo.end());
  h["band_hi"] = std::vector<int>(band.hi.begin(), band.hi.end());
  h["reach"] = reach;
  h["skin"] = skin;
  YAML::Emitter out;
  out << YAML::Flow << h;
  return out.c_str();
}

DpdGridSettings grid_settings(const ConcurrentParams& cp, const DpdModel& model) {
  DpdGridSettings s;
  s.cell_size = cp.grid.cell_size();
  s.flip = cp.flip;
  for (const auto& m : model.group_motions) s.rigid.push_back({m.mask, m.velocity, m.free_body});
  return s;
}

// The DPD part's owned particles, at unwrapped positions.
struct DpdView {
  std::vector<Vec3> x;
  std::vector<double> mass;
  coupling::ParticleView view(const DpdEngine& e) {
    const DpdParticles& p = e.particles();
    const OrthogonalBox& box = e.domain().box();
    x.resize(e.owned());
    mass.resize(e.owned());
    for (std::size_t i = 0; i < e.owned(); ++i) {
      for (int a = 0; a < 3; ++a) x[i][a] = p.x[i][a] + p.image[i][a] * box.length(a);
      mass[i] = p.mass(i);
    }
    return {e.owned(), p.id, x, p.v, mass, p.group_mask};
  }
};

// The body's extent along an axis, outermost sites plus half a plane
// spacing on each side (an fcc crystal of n cells spans n a).
double body_extent(const DpdParticles& all, int axis, double plane) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& x : all.x) {
    lo = std::min(lo, x[static_cast<std::size_t>(axis)]);
    hi = std::max(hi, x[static_cast<std::size_t>(axis)]);
  }
  return hi - lo + plane;
}

// Grip stress against strain, both grips held at their velocities.
struct TensionSeries {
  coupling::TensionProbe probe;
  std::uint32_t left = 0, right = 0;
  double pull_rate = 0.0;  // Å/ps, the grips' separation speed
  double length = 0.0, area = 0.0;
  std::vector<double> strain, stress, grip_stress;  // 1, GPa, GPa

  TensionSeries(const coupling::TensionProbe& t, const DpdModel& m, const DpdParticles& all,
                double plane)
      : probe(t), left(m.group_mask(t.left_grip)), right(m.group_mask(t.right_grip)) {
    const auto a = static_cast<std::size_t>(t.axis);
    for (const auto& g : m.group_motions) {
      if (g.mask == left) pull_rate -= g.velocity[a];
      if (g.mask == right) pull_rate += g.velocity[a];
    }
    length = body_extent(all, t.axis, plane);
    area = 1.0;
    for (int b = 0; b < 3; ++b) {
      if (b != t.axis) area *= body_extent(all, b, plane);
    }
  }
  // The body's mean axial stress from the DPD part's conservative virial
  // and the MPM part's sum of stress times volume (both eV), over the
  // initial cross-section times the current length, as dpd_run's tension
  // measures it; and the grips' holding forces (each part's plus the
  // other's) over the initial cross-section.
  void add(double t, double dpd_virial, double mpm_stress_volume, double f_left, double f_right) {
    const double e = pull_rate * t / length;
    constexpr double kGPa = units::kBarPerEvPerA3 / units::kBarPerGPa;  // eV/Å^3 to GPa
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
    if (n >= 3) r.add_scalar("youngs_modulus", (n * sxy - sx * sy) / (n * sxx - sx * sx), "GPa");
    if (!stress.empty()) {
      r.add_scalar("max_stress", *std::max_element(stress.begin(), stress.end()), "GPa");
    }
  }
};

std::vector<std::uint32_t> motion_masks(const DpdModel& m) {
  std::vector<std::uint32_t> out;
  for (const auto& g : m.group_motions) out.push_back(g.mask);
  return out;
}

// The DPD part's particles, one H5MD frame, each rank writing its own.
class DpdPartTrajectory {
 public:
  DpdPartTrajectory(const DpdEngine& e, const std::filesystem::path& path) {
    H5mdWriter::Options o;
    o.path = path.string();
    o.creator_version = "dpd_driver (concurrent)";
    o.periodic = e.domain().box().periodic;
    o.velocities = true;
    const DpdParticles& p = e.particles();
    const std::vector<std::int64_t> ids(p.id.begin(), p.id.begin() + static_cast<long>(e.owned()));
    const std::vector<int> types(p.type.begin(), p.type.begin() + static_cast<long>(e.owned()));
    writer_ = std::make_unique<H5mdWriter>(e.comm(), o, ids, types);
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

}  // namespace

void ConcurrentStage::run(StageContext& ctx) {
  const YAML::Node& p = ctx.params();
  const ConcurrentParams cp = coupling::concurrent_params(p);
  const MPI_Comm inter = ctx.peer("mpm_driver");
  if (inter == MPI_COMM_NULL) {
    throw Error(fmt::format("stage '{}': mpm_driver is not running", ctx.stage()));
  }
  const YAML::Node material = ctx.material(cp.material);
  DpdModel model = build_dpd_model(p, material, stage_seed(ctx.seed(), ctx.stage()), ctx.stage());
  // A state from an earlier stage may lie a little outside the box on a
  // periodic axis (positions wrap at list builds only); the regions see it
  // inside.
  wrap_periodic_axes(model.particles, model.box, model.particles.size());
  const double plane = 0.5 * material["lattice_constant"].as<double>();
  std::optional<TensionSeries> tension;
  if (cp.tension) tension.emplace(*cp.tension, model, model.particles, plane);
  SplitBody body = split_body(model.particles, cp);
  // Partners within the list's reach, chosen afresh when either side has
  // moved half the skin.
  const double reach =
      std::max(model.pair->cutoff(), model.settings.friction.cutoff) + model.settings.skin;
  const grid::NodeBox band = interface_band(body, cp, reach);
  coupling::hand_over(
      inter, ctx.comm(),
      {header_yaml(model.group_names, band, reach, model.settings.skin), body.mpm_rows});
  const auto dpd_count = static_cast<double>(body.dpd.size());
  const auto mpm_count = static_cast<double>(body.mpm_rows.size() / kRowWidth);

  DpdEngine engine(ctx.comm(), model.box, std::move(model.pair), model.settings,
                   std::move(body.dpd));
  engine.set_prescribed_groups(model.prescribed_mask);
  engine.set_rigid_bodies(model.rigid_bodies);
  DpdGridStep grid(engine, grid_settings(cp, model), cp.grid, cp.periodic);
  ConcurrentDpdSide side(engine, grid, 0);
  int remote = 0;
  MPI_Comm_remote_size(inter, &remote);
  const grid::GridPartition theirs(cp.grid, cp.periodic, remote);
  coupling::CrossProgramLink link(inter, side, grid.partition(), theirs, band, reach);
  coupling::CouplingScheme scheme({&side}, link, cp.interface);

  DpdView view;
  coupling::ConcurrentProbes probes(ctx.comm(), cp, model.group_names,
                                    0.5 * material["lattice_constant"].as<double>(),
                                    view.view(engine));
  // The whole body's mass and momentum: this part's and mpm_driver's.
  const double body_mass =
      coupling::swap_scalar(inter, ctx.comm(), dpd_count * engine.particles().mass_per_type[0]) +
      dpd_count * engine.particles().mass_per_type[0];
  std::vector<double> opening_t, opening, potential, interface_energy, internal, mass;
  std::array<double, 3> p0{};
  double worst_dp = 0.0;
  auto sample = [&](std::int64_t n) {
    const auto v = view.view(engine);
    probes.sample(n, v);
    // DPD pairs, and half of each pair with an MPM point (the other half
    // would be the MPM side's; its continuum energy is the stored energy).
    const ThermoState thermo = engine.thermo(true);            // one extra pair pass a sample
    const double own = engine.pair_energy_without_partners();  // and one more
    potential.push_back(own);
    interface_energy.push_back(thermo.potential - own);
    internal.push_back(thermo.internal);
    mass.push_back(probes.mass());
    std::array<double, 3> total{};
    for (std::size_t a = 0; a < 3; ++a) {
      total[a] =
          probes.momentum()[a] + coupling::swap_scalar(inter, ctx.comm(), probes.momentum()[a]);
    }
    if (n == 0) p0 = total;
    for (std::size_t a = 0; a < 3; ++a) worst_dp = std::max(worst_dp, std::abs(total[a] - p0[a]));
    if (tension) {
      const auto& reactions = grid.solver().point_velocity_reactions();
      const auto masks = motion_masks(model);
      const int a = tension->probe.axis;
      double f[2] = {coupling::grip_force(ctx.comm(), reactions, masks, tension->left, a),
                     coupling::grip_force(ctx.comm(), reactions, masks, tension->right, a)};
      for (double& x : f) x += coupling::swap_scalar(inter, ctx.comm(), x);
      const double w = thermo.virial[static_cast<std::size_t>(a)];
      const double sv = coupling::swap_scalar(inter, ctx.comm(), 0.0);
      tension->add(static_cast<double>(n) * cp.time_step, w, sv, f[0], f[1]);
    }
    if (cp.opening) {
      const auto mine = probes.opening_moments(v);
      opening_t.push_back(static_cast<double>(n) * cp.time_step);
      opening.push_back(coupling::ConcurrentProbes::opening(
          mine, coupling::swap_values(inter, ctx.comm(), mine)));
    }
  };

  std::unique_ptr<DpdPartTrajectory> trajectory;
  if (cp.particles_every > 0) {
    trajectory =
        std::make_unique<DpdPartTrajectory>(engine, ctx.stage_dir() / "dpd_particles.h5md");
    trajectory->write(engine, 0, 0.0);
  }
  probes.track(0, view.view(engine));
  sample(0);
  const auto started = std::chrono::steady_clock::now();
  for (std::int64_t n = 1; n <= cp.steps; ++n) {
    set_current_step(n);
    scheme.step_naming(cp.part(coupling::Solver::kDpd));
    probes.track(n, view.view(engine));
    if (n % cp.sample_every == 0 || n == cp.steps) sample(n);
    if (trajectory && (n % cp.particles_every == 0 || n == cp.steps)) {
      trajectory->write(engine, n, static_cast<double>(n) * cp.time_step);
    }
    ctx.progress(n, cp.steps, static_cast<double>(n) * cp.time_step, "concurrent");
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  auto& r = ctx.results();
  if (trajectory)
    r.files.push_back((std::filesystem::path(ctx.stage()) / "dpd_particles.h5md").string());
  r.attributes["interface"] = cp.interface_name;
  r.add_scalar("dpd_particles", dpd_count, "1");
  r.add_scalar("mpm_points", mpm_count, "1");
  r.add_scalar("dpd_temperature", engine.thermo(false).temperature, "K");
  // c = sqrt(E / rho) of the MPM material, bar Å³/(g/mol) to Å²/ps².
  const double a = cp.lattice_constant.value_or(material["lattice_constant"].as<double>());
  const double rho = 4.0 * material["mass"].as<double>() / (a * a * a);
  const double c = std::sqrt(cp.youngs_modulus / rho / units::kBarPerEvPerA3 / units::kMvv2e);
  r.add_scalar("momentum_change", worst_dp / (body_mass * c), "1");
  if (cp.opening && !opening.empty()) report_opening(r, opening_t, opening);
  if (cp.steps > 0 && seconds > 0.0) {
    r.add_scalar("steps_per_second", static_cast<double>(cp.steps) / seconds, "1/s");
  }
  probes.report(r, "dpd");
  r.add_column("dpd_ledger", "potential_energy", "eV", potential);
  r.add_column("dpd_ledger", "interface_pair_energy", "eV", interface_energy);
  r.add_column("dpd_ledger", "internal_energy", "eV", internal);
  r.add_column("dpd_ledger", "mass", "g/mol", mass);
  coupling::report_exchanges(r, ctx.comm(), "dpd", link.nodal_profile(), link.partner_profile(),
                             cp.steps, seconds);
  if (tension) tension->report(r);
  // Bytes the DPD part's ranks sent in the nodal sums and received as
  // partners, per step, summed over its ranks.
  double bytes[2] = {static_cast<double>(link.nodal_profile().bytes_sent),
                     static_cast<double>(link.partner_profile().bytes_received)};
  MPI_Allreduce(MPI_IN_PLACE, bytes, 2, MPI_DOUBLE, MPI_SUM, ctx.comm());
  const double steps = std::max<double>(1.0, static_cast<double>(cp.steps));
  r.add_scalar("nodal_sum_bytes_per_step", bytes[0] / steps, "1");
  r.add_scalar("partner_bytes_per_step", bytes[1] / steps, "1");
}

}  // namespace pbms::dpd
