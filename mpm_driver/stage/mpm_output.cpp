#include "mpm_output.hpp"

namespace pbms::mpm {

MpmOutput::MpmOutput(const MpmEngine& engine, const MpmRunParams& params,
                     const std::filesystem::path& stage_dir, const std::string& stage,
                     bool resuming)
    : params_(params), stage_(stage) {
  const auto& g = engine.model().grid;
  for (std::size_t a = 0; a < 3; ++a) edges_[a] = g.upper()[a] - g.origin()[a];
  // Every rank writes the points it holds, each at the row of its id, so
  // the file does not depend on the decomposition and no rank gathers them.
  if (params.particles_every > 0) {
    H5mdWriter::Options o;
    o.path = (stage_dir / "particles.h5md").string();
    o.creator_version = "mpm_driver";
    o.periodic = engine.model().periodic;
    o.metal_units = params.metal_units;
    o.velocities = true;
    const auto& ids = engine.points().id;
    particle_options_ = o;
    if (!resuming) {
      particles_ =
          std::make_unique<H5mdWriter>(engine.comm(), o, ids, std::vector<int>(ids.size(), 0));
    }
  }
  grid_base_ = (stage_dir / "grid").string();
  if (params.grid_every > 0 && !resuming) {
    grid_ = std::make_unique<GridFieldWriter>(engine.comm(), grid_base_, g, engine.owned_nodes());
  }
}

void MpmOutput::resume(const MpmEngine& engine, std::int64_t last_step) {
  if (params_.particles_every > 0) {
    particles_ =
        H5mdWriter::reopen(engine.comm(), particle_options_, engine.points().id, last_step);
  }
  if (params_.grid_every > 0) {
    grid_ = GridFieldWriter::reopen(engine.comm(), grid_base_, engine.model().grid,
                                    engine.owned_nodes(), last_step);
  }
}

void MpmOutput::write(const MpmEngine& engine, std::int64_t step, double t) {
  if (params_.particles_every > 0 && step % params_.particles_every == 0)
    write_particles(engine, step, t);
  if (grid_ && step > 0 && step % params_.grid_every == 0) write_grid(engine, step, t);
}

void MpmOutput::write_particles(const MpmEngine& engine, std::int64_t step, double t) {
  const grid::MaterialPoints& pts = engine.points();
  std::vector<double> x, v;
  x.reserve(3 * pts.size());
  v.reserve(3 * pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    x.insert(x.end(), pts.x[i].begin(), pts.x[i].end());
    v.insert(v.end(), pts.v[i].begin(), pts.v[i].end());
  }
  particles_->write_frame(step, t, edges_, pts.id, x, v);
}

void MpmOutput::write_grid(const MpmEngine& engine, std::int64_t step, double t) {
  const grid::MpmSolver& solver = engine.solver();
  const grid::NodeBox owned = engine.owned_nodes();
  const auto& local = solver.patch().nodes;
  std::vector<double> mass, vel;
  for (int k = owned.lo[2]; k < owned.hi[2]; ++k) {
    for (int j = owned.lo[1]; j < owned.hi[1]; ++j) {
      for (int i = owned.lo[0]; i < owned.hi[0]; ++i) {
        const auto li = static_cast<std::size_t>(local.local_index({i, j, k}));
        mass.push_back(solver.nodal_mass(li));
        const auto& v = solver.nodal_velocity(li);
        vel.insert(vel.end(), v.begin(), v.end());
      }
    }
  }
  const bool metal = params_.metal_units;
  grid_->write_frame(step, t,
                     {{"mass", metal ? "g/mol" : "1", 1, mass.data()},
                      {"velocity", metal ? "Å/ps" : "1", 3, vel.data()}});
}

std::vector<std::string> MpmOutput::files() const {
  std::vector<std::string> out;
  const std::filesystem::path dir(stage_);
  if (particles_) out.push_back((dir / "particles.h5md").string());
  if (grid_) {
    out.push_back((dir / "grid.h5").string());
    out.push_back((dir / "grid.xdmf").string());
  }
  return out;
}

}  // namespace pbms::mpm
