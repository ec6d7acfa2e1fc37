// The MPM part of a concurrent stage's body on the ranks of `comm`: the
// points the DPD part handed over (coupling::BodyHandover), as linear elastic
// material points on the shared grid, and the gas around the body when the
// stage has one (ideal-gas points, the box's faces walls), with their
// coupling side. mpm_driver's
// concurrent_mpm_part builds it on its ranks; the monolithic reference of
// the split test (tests/tools/concurrent_monolithic.cpp) builds it on one
// process beside the DPD part.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "engine/concurrent_mpm_side.hpp"
#include "engine/mpm_engine.hpp"
#include "materials/ideal_gas.hpp"
#include "pbms/coupling/body_handover.hpp"
#include "pbms/coupling/concurrent_params.hpp"

namespace pbms::mpm {

class MpmPartOfBody {
 public:
  MpmPartOfBody(MPI_Comm comm, const coupling::ConcurrentParams& cp,
                const coupling::BodyHandover& body);

  [[nodiscard]] const std::vector<std::string>& group_names() const { return groups_; }
  [[nodiscard]] const grid::NodeBox& band() const { return band_; }
  [[nodiscard]] double reach() const { return reach_; }
  // The fcc lattice constant the points sit on (Å).
  [[nodiscard]] double lattice_constant() const { return lattice_constant_; }

  // Before step `step`: the held groups on a velocity ramp take that
  // step's velocity.
  void ramp_grips(std::int64_t step);
  // After step `step`: the gas's specific internal energy moves dt / tau of
  // the way to its target (gas.heat_bath_time), and its pressure with it.
  // The target is the starting value, or with gas.ramp_time that value times
  // the fraction of the ramp done.
  void hold_gas_temperature(std::int64_t step);

  // The gas's material index, -1 without gas; the group of the gas points
  // away from the body (gas.probe_distance), where its pressure is measured.
  [[nodiscard]] int gas_material() const { return gas_; }
  static constexpr const char* kGasAwayGroup = "gas_away_from_body";

  [[nodiscard]] MpmEngine& engine() { return *engine_; }
  [[nodiscard]] ConcurrentMpmSide& side() { return *side_; }

 private:
  // The handed-over points on the shared grid: the body's sites as the
  // continuum, the gas's as the gas. Rigid and frozen groups with points
  // here are held at their velocity, as an MPM grip is.
  [[nodiscard]] MpmModel model_of(const coupling::ConcurrentParams& cp,
                                  const coupling::BodyHandover& body) const;

  std::vector<std::string> groups_;
  int continuum_ = -1, gas_ = -1;  // material indices, -1 when absent
  const IdealGas* gas_model_ = nullptr;
  double gas_energy_ = 0.0;      // the gas's starting specific internal energy
  double gas_relaxation_ = 0.0;  // dt / tau, 0 without a heat bath
  double gas_ramp_steps_ = 0.0;  // steps over which the bath's target rises; 0: none
  grid::NodeBox band_;
  double reach_ = 0.0, lattice_constant_ = 0.0, time_step_ = 0.0;
  std::unique_ptr<MpmEngine> engine_;
  std::unique_ptr<ConcurrentMpmSide> side_;
};

}  // namespace pbms::mpm
