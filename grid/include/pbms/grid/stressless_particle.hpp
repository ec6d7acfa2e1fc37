// The "material" of particles that carry no stress because their
// interactions come to the grid as point forces instead: the DPD particles
// of the DPD/MPM-grid model (seed §2.4, s-3b), whose pair forces are
// mapped to the nodes where an MPM point's stress divergence would be. The
// solver then advances them through the grid exactly as it does material
// points. Not in the registry: no workflow names it; a coupling scheme
// builds it.
#pragma once

#include "pbms/grid/material.hpp"

namespace pbms::grid {

class StresslessParticle final : public Material {
 public:
  static constexpr std::string_view kStyle = "stressless_particle";
  [[nodiscard]] std::string_view style() const override { return kStyle; }
  // The stress stays zero whatever the particles do.
  void update(const Mat3& /*velocity_gradient*/, double /*dt*/,
              MaterialPointState& state) const override {
    state.stress = {};
  }
  // No signal travels through the grid from these particles; their own
  // time-step bound is the pair style's.
  [[nodiscard]] double wave_speed(const MaterialPointState& /*state*/) const override {
    return 0.0;
  }
  [[nodiscard]] double stored_energy_density(const MaterialPointState& /*state*/) const override {
    return 0.0;
  }
  [[nodiscard]] bool tracks_deformation() const override { return false; }
};

}  // namespace pbms::grid
