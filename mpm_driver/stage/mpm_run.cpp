#include "mpm_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "mpm_model.hpp"
#include "mpm_probes.hpp"
#include "pbms/analysis/statistics.hpp"
#include "pbms/error.hpp"
#include "pbms/grid/grid_partition.hpp"
#include "pbms/io/grid_field_writer.hpp"
#include "pbms/io/h5md_writer.hpp"
#include "pbms/mpi/comm.hpp"
#include "pbms/mpi/halo_sum.hpp"
#include "point_migration.hpp"
#include "wave_front.hpp"

namespace pbms::mpm {
namespace {

double allreduce(MPI_Comm comm, double v, MPI_Op op) {
  double out = 0.0;
  mpi::check(MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, op, comm), "MPI_Allreduce");
  return out;
}

// Every rank's rows of `width` doubles, gathered on rank 0 (empty
// elsewhere).
std::vector<double> gather_rows(MPI_Comm comm, const std::vector<double>& local) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int n = static_cast<int>(local.size());
  std::vector<int> counts(static_cast<size_t>(size)), displs(static_cast<size_t>(size));
  mpi::check(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm), "MPI_Gather");
  std::vector<double> all;
  if (rank == 0) {
    int total = 0;
    for (size_t r = 0; r < counts.size(); ++r) {
      displs[r] = total;
      total += counts[r];
    }
    all.resize(static_cast<size_t>(total));
  }
  mpi::check(MPI_Gatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                         MPI_DOUBLE, 0, comm),
             "MPI_Gatherv");
  return all;
}

// Rows sorted by their first value (a global id).
std::vector<double> sorted_rows(const std::vector<double>& rows, size_t width) {
  const size_t n = rows.size() / width;
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return rows[a * width] < rows[b * width]; });
  std::vector<double> out;
  out.reserve(rows.size());
  for (const size_t i : order)
    out.insert(out.end(), rows.begin() + i * width, rows.begin() + (i + 1) * width);
  return out;
}

}  // namespace

void MpmRunStage::run(StageContext& ctx) {
  const YAML::Node& p = ctx.params();
  MPI_Comm comm = ctx.comm();
  const int rank = ctx.rank();
  const bool metal = p["units"].as<std::string>() == "metal";

  // Materials the bodies use, in order of first use.
  std::vector<std::string> mat_names;
  std::vector<YAML::Node> mat_entries;
  for (const auto& b : p["bodies"]) {
    const auto name = b["material"].as<std::string>();
    if (std::find(mat_names.begin(), mat_names.end(), name) != mat_names.end()) continue;
    mat_names.push_back(name);
    mat_entries.push_back(ctx.material(name));
  }
  MaterialSet materials = materials_from_yaml(mat_names, mat_entries, metal);
  MpmModel model = build_model(p, materials);
  const int64_t total_points = static_cast<int64_t>(model.points.size());

  // Decomposition: every rank built every point; each keeps the ones its
  // cells hold.
  const grid::GridPartition partition(model.grid, model.periodic, ctx.size());
  mpi::HaloSum halo(comm, partition);
  for (size_t i = model.points.size(); i-- > 0;) {
    if (partition.owner_of(model.points.x[i]) != rank) model.points.erase(i);
  }
  // erase() swapped points around; restore id order for reproducible output.
  {
    MaterialPoints sorted;
    std::vector<size_t> order(model.points.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return model.points.id[a] < model.points.id[b]; });
    MaterialPoints& src = model.points;
    for (const size_t i : order) {
      sorted.add(src.id[i], src.x[i], src.volume0[i], src.state[i], src.material[i], src.groups[i]);
      sorted.v.back() = src.v[i];
      sorted.mass.back() = src.mass[i];
      sorted.work.back() = src.work[i];
    }
    model.points = std::move(sorted);
  }
  MaterialPoints& pts = model.points;
  double min_mass = std::numeric_limits<double>::infinity();
  for (const double m : pts.mass) min_mass = std::min(min_mass, m);
  model.options.reference_point_mass = allreduce(comm, min_mass, MPI_MIN);

  GridPatch patch{model.grid, partition.nodes_of(rank), model.periodic, {}};
  if (!halo.empty()) {
    patch.sum_shared = [&halo](double* data, int components, int stride) {
      halo.sum(data, components, stride);
    };
  }
  MpmSolver solver(patch, grid::ShapeFunctionRegistry::create(model.shape_function),
                   std::move(materials.models), model.options);

  // Time step: the CFL bound h / max(c + |v|) over all points.
  const double bound = allreduce(comm, solver.stable_time_step(pts), MPI_MIN);
  double dt = 0.0;
  if (p["time_step"].as<std::string>() == "auto") {
    dt = p["courant"].as<double>() * bound;
  } else {
    dt = p["time_step"].as<double>();
    if (dt > bound) {
      const char* unit = metal ? " ps" : "";
      throw Error(fmt::format(
          "stage '{}': time_step {:.6g}{} exceeds the CFL bound h / max(c + |v|) = {:.6g}{} "
          "(h = {:g}); use a smaller time_step or `time_step: auto`",
          ctx.stage(), dt, unit, bound, unit, model.grid.cell_size()));
    }
  }
  const double duration = p["duration"].as<double>();
  const auto steps = static_cast<int64_t>(std::ceil(duration / dt - 1e-9));
  const int64_t sample_every = p["sample_every"].as<int64_t>();
  const int64_t particles_every = p["particles_every"].as<int64_t>();
  const int64_t grid_every = p["grid_every"].as<int64_t>();

  MpmProbes probes(p["probes"], model, metal);
  std::vector<std::vector<double>> samples(probes.columns().size());
  std::vector<double> sample_step, sample_time;
  std::vector<double> sums, maxima, reduced_sums, reduced_max;

  // Wave-front analysis of a step-loaded bar.
  const YAML::Node wf = p["wave_front"];
  StepLoadedBar bar;
  uint32_t bar_mask = 0;
  std::vector<double> front_t, front_s;
  double plateau = std::nan(""), rms = std::nan(""), variation = std::nan("");
  double profile_t_done = -1.0;
  int64_t plateau_step = -1, profile_step = -1;
  std::vector<double> profile_rows;
  if (wf) {
    bar_mask = model.group_mask(wf["group"].as<std::string>());
    bar.loaded_end = wf["loaded_end"].as<double>();
    bar.fixed_end = wf["fixed_end"].as<double>();
    bar.traction = wf["traction"].as<double>();
    double c = 0.0;
    for (size_t i = 0; i < pts.size(); ++i) {
      if (pts.in_group(i, bar_mask)) {
        c = solver.material(pts.material[i]).wave_speed(pts.state[i]) *
            std::sqrt(model.options.units.stress_volume_to_energy *
                      model.options.units.force_per_mass_to_accel);
        break;
      }
    }
    bar.wave_speed = allreduce(comm, c, MPI_MAX);
    plateau_step = std::llround(0.8 * bar.transit_time() / dt);
    profile_step = std::llround(wf["profile_time"].as<double>() / dt);
    if (profile_step > steps) {
      throw Error(fmt::format("stage '{}': wave_front.profile_time is after the end of the run",
                              ctx.stage()));
    }
  }
  auto bar_profile = [&]() {
    std::vector<double> rows;
    for (size_t i = 0; i < pts.size(); ++i) {
      if (!pts.in_group(i, bar_mask)) continue;
      rows.push_back(static_cast<double>(pts.id[i]));
      rows.push_back(pts.x[i][0]);
      rows.push_back(pts.state[i].stress.voigt[0]);
      rows.push_back(pts.volume(i));
    }
    return sorted_rows(gather_rows(comm, rows), 4);
  };

  // Output writers. Particles are gathered to rank 0 and written in id
  // order, so files do not depend on the decomposition.
  std::unique_ptr<H5mdWriter> h5md;
  std::unique_ptr<GridFieldWriter> grid_out;
  std::vector<int64_t> all_ids;
  const auto edges = std::array<double, 3>{model.grid.upper()[0] - model.grid.origin()[0],
                                           model.grid.upper()[1] - model.grid.origin()[1],
                                           model.grid.upper()[2] - model.grid.origin()[2]};
  if (particles_every > 0 && rank == 0) {
    H5mdWriter::Options o;
    o.path = (ctx.stage_dir() / "particles.h5md").string();
    o.creator_version = "mpm_driver";
    o.periodic = model.periodic;
    o.metal_units = metal;
    o.velocities = true;
    all_ids.resize(static_cast<size_t>(total_points));
    std::iota(all_ids.begin(), all_ids.end(), int64_t{0});
    std::vector<int> species(all_ids.size(), 0);
    h5md = std::make_unique<H5mdWriter>(MPI_COMM_SELF, o, all_ids, species);
  }
  const grid::NodeBox owned = partition.owned_nodes_of(rank);
  if (grid_every > 0) {
    grid_out = std::make_unique<GridFieldWriter>(comm, (ctx.stage_dir() / "grid").string(),
                                                 model.grid, owned);
  }
  auto write_output = [&](int64_t step, double t) {
    if (particles_every > 0 && step % particles_every == 0) {
      std::vector<double> rows;
      rows.reserve(pts.size() * 7);
      for (size_t i = 0; i < pts.size(); ++i) {
        rows.push_back(static_cast<double>(pts.id[i]));
        rows.insert(rows.end(), pts.x[i].begin(), pts.x[i].end());
        rows.insert(rows.end(), pts.v[i].begin(), pts.v[i].end());
      }
      const auto all = sorted_rows(gather_rows(comm, rows), 7);
      if (h5md) {
        std::vector<double> x, v;
        for (size_t r = 0; r + 7 <= all.size(); r += 7) {
          x.insert(x.end(), all.begin() + r + 1, all.begin() + r + 4);
          v.insert(v.end(), all.begin() + r + 4, all.begin() + r + 7);
        }
        h5md->write_frame(step, t, edges, x, v);
      }
    }
    if (grid_out && step > 0 && step % grid_every == 0) {
      const auto& local = patch.nodes;
      std::vector<double> mass, vel;
      for (int k = owned.lo[2]; k < owned.hi[2]; ++k) {
        for (int j = owned.lo[1]; j < owned.hi[1]; ++j) {
          for (int i = owned.lo[0]; i < owned.hi[0]; ++i) {
            const auto li = static_cast<size_t>(local.local_index({i, j, k}));
            mass.push_back(solver.nodal_mass(li));
            const auto& v = solver.nodal_velocity(li);
            vel.insert(vel.end(), v.begin(), v.end());
          }
        }
      }
      grid_out->write_frame(step, t,
                            {{"mass", metal ? "g/mol" : "1", 1, mass.data()},
                             {"velocity", metal ? "Å/ps" : "1", 3, vel.data()}});
    }
  };

  auto sample = [&](int64_t step, double t) {
    probes.local(pts, solver, model.bc, sums, maxima);
    reduced_sums.resize(sums.size());
    reduced_max.resize(maxima.size());
    if (!sums.empty()) {
      mpi::check(MPI_Allreduce(sums.data(), reduced_sums.data(), static_cast<int>(sums.size()),
                               MPI_DOUBLE, MPI_SUM, comm),
                 "MPI_Allreduce (probes)");
    }
    if (!maxima.empty()) {
      mpi::check(MPI_Allreduce(maxima.data(), reduced_max.data(), static_cast<int>(maxima.size()),
                               MPI_DOUBLE, MPI_MAX, comm),
                 "MPI_Allreduce (probes)");
    }
    auto values = probes.values(reduced_sums, reduced_max);
    if (step == 0) {
      probes.set_reference(values);
      values = probes.values(reduced_sums, reduced_max);
    }
    for (size_t c = 0; c < values.size(); ++c) samples[c].push_back(values[c]);
    sample_step.push_back(static_cast<double>(step));
    sample_time.push_back(t);
    if (wf && t > 0.1 * bar.transit_time() && t < 0.9 * bar.transit_time()) {
      std::vector<double> x, sxx;
      for (size_t i = 0; i < pts.size(); ++i) {
        if (!pts.in_group(i, bar_mask)) continue;
        x.push_back(pts.x[i][0]);
        sxx.push_back(pts.state[i].stress.voigt[0]);
      }
      front_t.push_back(t);
      front_s.push_back(allreduce(comm, front_distance(bar, x, sxx), MPI_MAX));
    }
  };

  // Steps. A steps: 0 run still samples and writes the initial state.
  double t = 0.0;
  sample(0, 0.0);
  write_output(0, 0.0);
  for (int64_t n = 1; n <= steps; ++n) {
    solver.step(pts, model.bc, dt);
    if (ctx.size() > 1) migrate_points(comm, partition, pts);
    t = static_cast<double>(n) * dt;
    if (n % sample_every == 0 || n == steps) sample(n, t);
    write_output(n, t);
    if (wf && n == plateau_step) {
      const auto rows = bar_profile();
      if (rank == 0) {
        std::vector<double> x, s, v;
        for (size_t r = 0; r + 4 <= rows.size(); r += 4) {
          x.push_back(rows[r + 1]);
          s.push_back(rows[r + 2]);
          v.push_back(rows[r + 3]);
        }
        plateau = plateau_stress(bar, t, x, s, v);
      }
    }
    if (wf && n == profile_step) {
      profile_rows = bar_profile();
      profile_t_done = t;
      if (rank == 0) {
        std::vector<double> x, s;
        for (size_t r = 0; r + 4 <= profile_rows.size(); r += 4) {
          x.push_back(profile_rows[r + 1]);
          s.push_back(profile_rows[r + 2]);
        }
        rms = rms_from_exact(bar, t, x, s);
        variation = excess_variation(bar, t, x, s);
      }
    }
    ctx.progress(n, steps, t, "mpm");
  }

  // Results (taken from rank 0).
  auto& r = ctx.results();
  const std::string time_unit = metal ? "ps" : "1";
  r.add_scalar("steps", static_cast<double>(steps), "1");
  r.add_scalar("time_step", dt, time_unit);
  r.add_scalar("particles", static_cast<double>(total_points), "1");
  r.add_column("probes", "step", "1", sample_step);
  r.add_column("probes", "time", time_unit, sample_time);
  for (size_t c = 0; c < samples.size(); ++c) {
    r.add_column("probes", probes.columns()[c], probes.units()[c], samples[c]);
  }
  if (probes.has_energy()) {
    const auto& e = samples[static_cast<size_t>(probes.energy_total_column())];
    const double e0 = e.front();
    double dev = 0.0;
    for (const double v : e) dev = std::max(dev, std::abs(v - e0));
    const double scale = std::abs(e0) > 0.0 ? std::abs(e0) : 1.0;
    r.add_scalar("energy_drift", (e.back() - e0) / scale, "1");
    r.add_scalar("energy_max_deviation", dev / scale, "1");
  }
  if (p["period_of"]) {
    const auto col = p["period_of"].as<std::string>();
    const auto it = std::find(probes.columns().begin(), probes.columns().end(), col);
    if (it == probes.columns().end()) {
      throw Error(fmt::format("stage '{}': period_of names no probe column ('{}'); columns: {}",
                              ctx.stage(), col, fmt::join(probes.columns(), ", ")));
    }
    r.add_scalar("period",
                 analysis::oscillation_period(
                     sample_time, samples[static_cast<size_t>(it - probes.columns().begin())]),
                 time_unit);
  }
  if (wf) {
    const std::string stress_unit = metal ? "bar" : "1";
    const std::string speed_unit = metal ? "Å/ps" : "1";
    if (front_t.size() < 3) {
      throw Error(fmt::format(
          "stage '{}': wave_front needs at least 3 samples before the first reflection; lower "
          "sample_every",
          ctx.stage()));
    }
    const auto fit = analysis::fit_line(front_t, front_s);
    r.add_scalar("wave_speed", fit.slope, speed_unit);
    r.add_scalar("exact_wave_speed", bar.wave_speed, speed_unit);
    if (plateau_step <= steps) r.add_scalar("plateau_stress", plateau, stress_unit);
    r.add_scalar("rms_from_exact", rms, stress_unit);
    r.add_scalar("excess_variation", variation, stress_unit);
    if (wf["rms_reference"]) {
      r.add_scalar("rms_ratio_mpm_over_ddmp", wf["rms_reference"].as<double>() / rms, "1");
    }
    if (wf["variation_reference"]) {
      r.add_scalar("variation_ratio_mpm_over_ddmp",
                   wf["variation_reference"].as<double>() / variation, "1");
    }
    r.add_column("front", "time", time_unit, front_t);
    r.add_column("front", "distance", metal ? "Å" : "1", front_s);
    std::vector<double> x, s, exact;
    for (size_t k = 0; k + 4 <= profile_rows.size(); k += 4) {
      x.push_back(profile_rows[k + 1]);
      s.push_back(profile_rows[k + 2]);
      exact.push_back(bar.exact_stress(profile_rows[k + 1], profile_t_done));
    }
    r.add_column("profile", "x", metal ? "Å" : "1", x);
    r.add_column("profile", "stress_xx", stress_unit, s);
    r.add_column("profile", "exact_stress_xx", stress_unit, exact);
    r.attributes["profile_time"] = fmt::format("{:.10g}", profile_t_done);
  }
  r.attributes["gradient"] = p["gradient"].as<std::string>();
  r.attributes["decomposition"] =
      fmt::format("{}x{}x{}", partition.dims()[0], partition.dims()[1], partition.dims()[2]);
  if (h5md) r.files.push_back((std::filesystem::path(ctx.stage()) / "particles.h5md").string());
  if (grid_out) {
    r.files.push_back((std::filesystem::path(ctx.stage()) / "grid.h5").string());
    r.files.push_back((std::filesystem::path(ctx.stage()) / "grid.xdmf").string());
  }
}

}  // namespace pbms::mpm
