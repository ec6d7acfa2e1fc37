#include "md_setup.hpp"

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms::md {

MdMaterial MdMaterial::from_yaml(const std::string& name, const YAML::Node& n) {
  MdMaterial m;
  m.name = name;
  const auto kind = n["kind"].as<std::string>();
  if (kind == "eam_alloy" || kind == "sutton_chen") {
    m.pair_style = "eam/alloy";
  } else if (kind == "eam_fs") {
    m.pair_style = "eam/fs";
  } else {
    throw Error(fmt::format("md_driver cannot simulate material kind '{}'", kind));
  }
  if (kind == "sutton_chen") {
    SuttonChenParameters p;
    p.epsilon = n["epsilon"].as<double>();
    p.a = n["a"].as<double>();
    p.c = n["c"].as<double>();
    p.n = n["n"].as<double>();
    p.m = n["m"].as<double>();
    p.cutoff = n["cutoff"].as<double>();
    p.smoothing = n["smoothing"].as<double>();
    m.sutton_chen = p;
  } else {
    m.potential = n["potential"].as<std::string>();
  }
  m.element = n["element"].as<std::string>();
  m.mass = n["mass"].as<double>();
  m.lattice = n["lattice"].as<std::string>();
  m.lattice_constant = n["lattice_constant"].as<double>();
  return m;
}

MdMaterial material_of(const StageContext& ctx, const std::string& name) {
  MdMaterial m = MdMaterial::from_yaml(name, ctx.material(name));
  if (!m.sutton_chen) return m;
  const auto file = ctx.stage_dir() / (name + ".sutton_chen.eam.alloy");
  m.potential = file.string();
  if (ctx.rank() == 0) {
    const SuttonChenParameters& p = *m.sutton_chen;
    // Four times the crystal's density: deeper than any compression a
    // stage reaches (10 GPa raises it by about a third).
    const double rho_max = 4.0 * crystal_density(p, m.lattice, m.lattice_constant);
    std::ofstream out(file);
    out << sutton_chen_setfl(p, {m.element, m.mass, m.lattice_constant, m.lattice, 0}, rho_max);
    if (!out) throw Error(fmt::format("cannot write the Sutton-Chen table {}", file.string()));
  }
  mpi::check(MPI_Barrier(ctx.comm()), "MPI_Barrier");
  return m;
}

void build_crystal(Lammps& lmp, const MdMaterial& m, double a, const std::array<int, 3>& cells,
                   const std::string& boundary) {
  lmp.command("units metal");
  lmp.command("atom_style atomic");
  lmp.command("atom_modify map array");
  lmp.command("boundary " + boundary);
  lmp.command(fmt::format("lattice {} {:.10g}", m.lattice, a));
  lmp.command(fmt::format("region box block 0 {} 0 {} 0 {}", cells[0], cells[1], cells[2]));
  lmp.command("create_box 1 box");
  lmp.command("create_atoms 1 box");
  lmp.command(fmt::format("mass 1 {:.10g}", m.mass));
  set_pair_style(lmp, m);
}

void set_pair_style(Lammps& lmp, const MdMaterial& m) {
  lmp.command("pair_style " + m.pair_style);
  lmp.command(fmt::format("pair_coeff * * {} {}", m.potential, m.element));
  lmp.command("neighbor 1.0 bin");
  lmp.command("neigh_modify every 1 delay 0 check yes");
}

int64_t steps_for(double time_ps, double timestep_ps) {
  return static_cast<int64_t>(std::llround(time_ps / timestep_ps));
}

int lammps_seed(uint64_t run_seed, uint64_t salt) {
  // splitmix64 finaliser: nearby run seeds give unrelated LAMMPS seeds.
  uint64_t z = run_seed + 0x9e3779b97f4a7c15ULL * (salt + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return 1 + static_cast<int>(z % 900000000ULL);
}

std::array<int, 3> cells_of(const YAML::Node& n) {
  return {n[0].as<int>(), n[1].as<int>(), n[2].as<int>()};
}

int64_t chunk_for(int64_t total_steps, int64_t trajectory_every) {
  int64_t chunk = std::max<int64_t>(1, total_steps / 100);
  if (trajectory_every > 0) {
    chunk = std::max<int64_t>(trajectory_every, chunk / trajectory_every * trajectory_every);
  }
  return chunk;
}

std::vector<double> column(const std::vector<std::vector<double>>& rows, size_t j) {
  std::vector<double> out;
  out.reserve(rows.size());
  for (const auto& r : rows) out.push_back(r.at(j));
  return out;
}

TrajectoryRecorder::TrajectoryRecorder(const StageContext& ctx, Lammps& lmp,
                                       const std::string& file, int64_t every,
                                       std::array<bool, 3> periodic, int64_t resumed_after)
    : ctx_(ctx), lmp_(lmp), every_(every) {
  if (every_ <= 0) return;
  relative_ = ctx.stage() + "/" + file;
  // LAMMPS gathers atoms by id to every rank; rank 0 writes the file alone.
  if (ctx.rank() == 0) {
    const auto n = lmp.natoms();
    ids_.resize(static_cast<size_t>(n));
    for (int64_t i = 0; i < n; ++i) ids_[static_cast<size_t>(i)] = i + 1;
    H5mdWriter::Options opt;
    opt.path = (ctx.stage_dir() / file).string();
    opt.creator = "pbms md_driver";
    opt.creator_version = fmt::format("LAMMPS {}", lmp.version());
    opt.periodic = periodic;
    opt.velocities = true;
    writer_ = resumed_after >= 0
                  ? H5mdWriter::reopen(MPI_COMM_SELF, opt, ids_, resumed_after)
                  : std::make_unique<H5mdWriter>(MPI_COMM_SELF, opt, ids_,
                                                 std::vector<int>(static_cast<size_t>(n), 0));
  }
}

void TrajectoryRecorder::maybe_write(int64_t step, double time_ps) {
  if (every_ <= 0 || step % every_ != 0) return;
  const auto x = lmp_.gather("x");
  const auto v = lmp_.gather("v");
  const std::array<double, 3> edges = {lmp_.thermo("lx"), lmp_.thermo("ly"), lmp_.thermo("lz")};
  if (writer_) writer_->write_frame(step, time_ps, edges, ids_, x, v);
}

}  // namespace pbms::md
