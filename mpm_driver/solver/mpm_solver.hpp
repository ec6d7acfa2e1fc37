// One explicit MPM time step on a regular background grid (Sulsky, Chen &
// Schreyer 1994; seed §2.4.2 steps s-1 to s-14), with update-stress-last or
// -first, a FLIP/PIC blend and plain or DDMP (dual-domain) gradients.
// Physics only: no MPI, no files; the driver owns decomposition and output.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "boundary_conditions.hpp"
#include "material_points.hpp"
#include "materials/material.hpp"
#include "pbms/grid/ddmp_gradient.hpp"
#include "pbms/grid/regular_grid.hpp"
#include "pbms/grid/shape_function.hpp"

namespace pbms::mpm {

enum class StressUpdate { kLast, kFirst };

// Conversion factors between the stress, force and acceleration units of a
// run: 1 for consistent units (the seed's 1-D bar), metal units otherwise.
struct UnitSystem {
  double stress_volume_to_energy = 1.0;  // sigma * V -> energy (bar Å^3 -> eV)
  double force_per_mass_to_accel = 1.0;  // f / m -> acceleration (eV/Å/(g/mol) -> Å/ps^2)
  static UnitSystem metal();
};

struct SolverOptions {
  StressUpdate stress_update = StressUpdate::kLast;
  double flip = 1.0;  // 1: FLIP, 0: PIC
  // Blend weight alpha of the plain gradient: 1 is plain MPM, 0 pure DDMP;
  // "face_vanishing" uses 4 xi (1 - xi) per axis (seed Appendix 2).
  bool ddmp = false;
  bool ddmp_face_vanishing = false;
  // Nodes lighter than this fraction of the lightest point's mass are left
  // out of the divisions (end of seed §2.4.2): their velocity would be noise.
  double small_mass_fraction = 1e-3;
  UnitSystem units;
};

struct EnergySummary {
  double kinetic = 0.0;
  double stored = 0.0;
  double dissipated = 0.0;
  [[nodiscard]] double total() const { return kinetic + stored + dissipated; }
};

class MpmSolver {
 public:
  MpmSolver(grid::RegularGrid grid, std::unique_ptr<grid::ShapeFunction> shape,
            std::vector<std::unique_ptr<Material>> materials, SolverOptions options);

  // Advances the points by dt. Throws pbms::Error naming the point (id,
  // position) if one leaves the grid.
  void step(MaterialPoints& points, const BoundaryConditions& bc, double dt);

  // The largest stable time step: h / max_p (c_p + |v_p|).
  [[nodiscard]] double stable_time_step(const MaterialPoints& points) const;
  [[nodiscard]] EnergySummary energy(const MaterialPoints& points) const;

  [[nodiscard]] const grid::RegularGrid& grid() const { return grid_; }
  [[nodiscard]] const Material& material(int i) const {
    return *materials_[static_cast<size_t>(i)];
  }
  // Nodal fields after the last step (for grid output).
  [[nodiscard]] const std::vector<double>& nodal_mass() const { return mass_; }
  [[nodiscard]] const std::vector<Vec3>& nodal_velocity() const { return velocity_; }

 private:
  void evaluate(const Vec3& x, int64_t id, grid::ShapeStencil& s) const;
  void map_mass_momentum(const MaterialPoints& points);
  void compute_velocity_gradients(const MaterialPoints& points, std::vector<Mat3>& L);
  void update_stress(MaterialPoints& points, const std::vector<Mat3>& L, double dt);
  void internal_forces(const MaterialPoints& points);
  void apply_node_constraints(const BoundaryConditions& bc, std::vector<Vec3>& field,
                              bool is_velocity) const;
  void prepare_ddmp(const MaterialPoints& points);
  double alpha(const MaterialPoints& points, size_t p) const;

  grid::RegularGrid grid_;
  std::unique_ptr<grid::ShapeFunction> shape_;
  std::vector<std::unique_ptr<Material>> materials_;
  SolverOptions opt_;
  double mass_floor_ = 0.0;
  std::vector<double> mass_;
  std::vector<Vec3> momentum_, force_, velocity_;
  std::vector<Mat3> L_;
  std::unique_ptr<grid::DualDomainOperator> dual_;
};

}  // namespace pbms::mpm
