// A copper bar periodic across and free along x, its lower half DPD
// particles (the DPD/MPM-grid model with the pair thermostat on) and its
// upper half elastic MPM points on the same fcc sites with the
// mesoparticle's mass: the body the split-equals-monolithic test and the
// concurrent_impact bench advance. Needs pbms_dpd, pbms_mpm and
// PBMS_SOURCE_DIR (tests/unit/cu_cg_morse.hpp).
#pragma once

#include <mpi.h>

#include <cmath>
#include <memory>

#include "cu_cg_morse.hpp"
#include "engine/concurrent_dpd_side.hpp"
#include "engine/concurrent_mpm_side.hpp"
#include "engine/dpd_engine.hpp"
#include "engine/dpd_grid_step.hpp"
#include "engine/mpm_engine.hpp"
#include "kernels/fcc_crystal.hpp"
#include "kernels/maxwell_boltzmann_velocities.hpp"
#include "materials/linear_elastic.hpp"

namespace pbms::testing {

constexpr double kMass = 508.368;   // 8 Cu atoms, g/mol
constexpr double kLattice = 7.230;  // a_cg, Å
constexpr double kDt = 0.01;        // ps
constexpr double kSkin = 1.0;       // Å, the DPD list's (DpdIntegratorSettings' default)
// E<100> and ν of the Morse mesoparticle at 298 K (dpd_elastic), GPa → bar.
constexpr double kYoung = 91.0e4, kPoisson = 0.35;
const std::array<bool, 3> kPeriodic{false, true, true};

struct ConcurrentBar {
  int cells_x = 8;       // fcc cells along x
  int cells_across = 4;  // fcc cells along y and z (periodic)
  int grid_across = 7;   // grid cells across: lattice planes off the node planes
  bool all_dpd = false;  // the whole bar DPD (the all-DPD reference)
  bool ddmp = false;     // DDMP gradients for the MPM points
  grid::PointMove move = grid::PointMove::kStepStart;  // both parts' (grid.move)

  [[nodiscard]] double h() const { return cells_across * kLattice / grid_across; }
  [[nodiscard]] double interface() const { return 0.5 * cells_x * kLattice; }
  [[nodiscard]] double length() const { return cells_x * kLattice; }
  [[nodiscard]] grid::RegularGrid grid() const {
    return grid::RegularGrid(
        {-3.3 * h(), 0.0, 0.0}, h(),
        {static_cast<int>(std::ceil(length() / h())) + 7, grid_across, grid_across});
  }
  [[nodiscard]] bool is_dpd(const dpd::Vec3& x) const { return all_dpd || x[0] < interface(); }
  // Nodes both halves can touch: a few node planes either side of the interface.
  [[nodiscard]] grid::NodeBox band() const {
    const grid::RegularGrid g = grid();
    const int i = static_cast<int>(std::floor((interface() - g.origin()[0]) / h()));
    return {{i - 3, 0, 0}, {i + 4, g.cells()[1] + 1, g.cells()[2] + 1}};
  }
};

inline dpd::FccCrystal whole_bar(const ConcurrentBar& bar) {
  dpd::FccCrystal c =
      dpd::fcc_crystal(bar.cells_x, bar.cells_across, bar.cells_across, kLattice, kMass);
  dpd::assign_maxwell_boltzmann_velocities(c.particles, 298.0, 11);
  c.box.periodic = kPeriodic;
  return c;
}

struct DpdPart {
  std::unique_ptr<dpd::DpdEngine> engine;
  std::unique_ptr<dpd::DpdGridStep> grid;
  std::unique_ptr<dpd::ConcurrentDpdSide> side;
};

inline DpdPart dpd_part(MPI_Comm comm, const ConcurrentBar& bar) {
  dpd::FccCrystal c = whole_bar(bar);
  dpd::DpdParticles mine;
  mine.mass_per_type = c.particles.mass_per_type;
  for (std::size_t i = 0; i < c.particles.size(); ++i) {
    if (bar.is_dpd(c.particles.x[i])) {
      mine.add(c.particles.id[i], 0, c.particles.x[i], c.particles.v[i]);
    }
  }
  dpd::DpdIntegratorSettings s;
  s.scheme = dpd::DpdScheme::kVelocityVerlet;
  s.dt = kDt;
  s.friction.gamma = 0.2;
  s.friction.cutoff = dpd::cu_cg_morse_parameters().cutoff;
  s.friction.temperature = 298.0;
  s.friction.seed = 42;
  s.skin = kSkin;
  DpdPart p;
  p.engine = std::make_unique<dpd::DpdEngine>(comm, c.box, dpd::cu_cg_morse(), s, std::move(mine));
  dpd::DpdGridSettings grid{bar.h(), 1.0, 4, {}};
  grid.move = bar.move;
  p.grid = std::make_unique<dpd::DpdGridStep>(*p.engine, grid, bar.grid(), kPeriodic);
  p.side = std::make_unique<dpd::ConcurrentDpdSide>(*p.engine, *p.grid, 0);
  return p;
}

struct MpmPart {
  std::unique_ptr<mpm::MpmEngine> engine;
  std::unique_ptr<mpm::ConcurrentMpmSide> side;
};

inline MpmPart mpm_part(MPI_Comm comm, const ConcurrentBar& bar) {
  const dpd::FccCrystal c = whole_bar(bar);
  mpm::MpmModel model;
  model.grid = bar.grid();
  model.periodic = kPeriodic;
  model.options.units = grid::UnitSystem::metal();
  model.options.small_mass_fraction = 0.0;  // as the DPD side's grid step
  model.options.ddmp = model.options.ddmp_face_vanishing = bar.ddmp;
  model.options.move = bar.move;
  const double volume = kLattice * kLattice * kLattice / 4.0;
  for (std::size_t i = 0; i < c.particles.size(); ++i) {
    if (bar.is_dpd(c.particles.x[i])) continue;
    grid::MaterialPointState s;
    s.density = kMass / volume;
    model.points.add(c.particles.id[i], c.particles.x[i], volume, s, 0);
    model.points.mass.back() = kMass;
    model.points.v.back() = c.particles.v[i];
  }
  mpm::MaterialSet materials;
  materials.models.push_back(std::make_unique<mpm::LinearElastic>(kYoung, kPoisson));
  materials.names.push_back("copper");
  materials.density.push_back(kMass / volume);
  MpmPart p;
  p.engine = std::make_unique<mpm::MpmEngine>(comm, std::move(model), std::move(materials));
  p.side = std::make_unique<mpm::ConcurrentMpmSide>(*p.engine, kDt, kSkin);
  return p;
}

}  // namespace pbms::testing
