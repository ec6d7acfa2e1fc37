// The constitutive model of an MPM material point, as the explicit solver sees
// it: a stress update over one step from the velocity gradient, plus what the
// solver needs for its time step and energy balance. Pure kernels: no MPI, no
// I/O, no configuration. Units are whatever the caller uses consistently; with
// stresses in bar and densities in g/mol/Å^3 the caller must convert moduli to
// (g/mol)/(Å ps^2) for wave_speed to come out in Å/ps.
#pragma once

#include <cstddef>
#include <string_view>

#include "pbms/grid/material_block.hpp"
#include "pbms/grid/material_point_state.hpp"
#include "pbms/grid/symmetric_tensor.hpp"

namespace pbms::grid {

class Material {
 public:
  virtual ~Material() = default;

  // The registry name, e.g. "linear_elastic".
  [[nodiscard]] virtual std::string_view style() const = 0;

  // Advances stress and history over one step of length dt, during which the
  // velocity gradient is velocity_gradient(i, j) = dv_i/dx_j (the MPM sum of
  // v_I (x) grad N_I; not symmetric). The same kernel serves update-stress-
  // first and update-stress-last: the solver decides when to call it. On entry
  // state.density already holds the end-of-step density (see
  // MaterialPointState); on exit state.stress is the end-of-step stress.
  virtual void update(const Mat3& velocity_gradient, double dt,
                      MaterialPointState& state) const = 0;

  // update() for points begin..end-1 of a block, each over its own
  // velocity gradient. The solver calls this for runs of points of one
  // material, which keeps the virtual call out of the per-point loop; a
  // material may override it with a loop the compiler vectorises across
  // points, which must give update()'s result to round-off.
  virtual void update_block(MaterialBlock& block, std::size_t begin, std::size_t end,
                            double dt) const {
    for (std::size_t i = begin; i < end; ++i) {
      MaterialPointState s = block.state(i);
      update(block.velocity_gradient(i), dt, s);
      block.set_state(i, s);
    }
  }

  // Fastest signal speed in the material at this state, for the CFL bound
  // dt < h / (c + |v|).
  [[nodiscard]] virtual double wave_speed(const MaterialPointState& state) const = 0;

  // Recoverable energy per unit current volume: elastic strain energy for
  // solids, internal energy for the gas. Kinetic + stored + dissipated is
  // conserved by a consistent solver.
  [[nodiscard]] virtual double stored_energy_density(const MaterialPointState& state) const = 0;
  // Whether the point's deformation gradient describes its material, so that
  // an inverted one is a failure. Not for particles whose structure comes
  // from their own pair forces (the DPD particles of the grid model), where
  // F is only the grid's velocity field integrated along their path.
  [[nodiscard]] virtual bool tracks_deformation() const { return true; }

  // Energy per unit volume turned into heat so far (plastic work).
  [[nodiscard]] virtual double dissipated_energy_density(const MaterialPointState&) const {
    return 0.0;
  }

  // A point at rest under hydrostatic pressure (tension negative) at the given
  // density. Throws pbms::Error if density is not positive or the pressure is
  // one the material cannot hold.
  [[nodiscard]] virtual MaterialPointState initial_state(double density, double pressure) const;
};

}  // namespace pbms::grid
