// The probes of a DPD stage: named columns sampled every N steps. Each
// probe adds this rank's share to sums (and minima/maxima for extents);
// the stage reduces them over ranks and turns them into column values.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dpd_model.hpp"
#include "dpd_stage_params.hpp"
#include "engine/dpd_engine.hpp"

namespace pbms::dpd {

class DpdProbes {
 public:
  DpdProbes(const std::vector<DpdProbeSpec>& probes, const DpdModel& model);

  [[nodiscard]] const std::vector<std::string>& columns() const { return columns_; }
  [[nodiscard]] const std::vector<std::string>& units() const { return units_; }
  [[nodiscard]] bool needs_potential() const { return needs_potential_; }

  // Collective: samples every probe (all ranks call it).
  [[nodiscard]] std::vector<double> sample(DpdEngine& engine, ThermoState& thermo);

  // The slabs' reference centres of mass (set at the first sample), four
  // numbers a probe, for a checkpoint; and back.
  [[nodiscard]] std::vector<double> references() const;
  void set_references(const std::vector<double>& values);

  // Centre of mass (unwrapped) of a group, all ranks; used by analyses too.
  [[nodiscard]] static Vec3 centre_of_mass(const DpdEngine& engine, std::uint32_t mask);
  // Largest minus smallest coordinate of a group along an axis.
  [[nodiscard]] static double extent(const DpdEngine& engine, std::uint32_t mask, int axis);
  // The pair force on a group's particles, eV/Å, over all ranks (collective).
  [[nodiscard]] static Vec3 group_force(const DpdEngine& engine, std::uint32_t mask);

 private:
  enum class Kind { kTemperature, kPressure, kEnergy, kMomentum, kSlab, kForce, kExtent };
  struct Probe {
    Kind kind;
    std::uint32_t mask = 0;
    int axis = 0;
    Vec3 reference{};  // slab: centre of mass at the first sample
    bool has_reference = false;
  };
  std::vector<Probe> probes_;
  std::vector<std::string> columns_, units_;
  bool needs_potential_ = false;
};

}  // namespace pbms::dpd
