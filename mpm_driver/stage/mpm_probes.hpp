// Quantities an mpm_run samples: each probe adds its rank-local partial sums
// (and maxima) to two flat arrays that the stage reduces over ranks in one
// call each, then turns the reduced numbers into its columns.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mpm_model.hpp"
#include "pbms/grid/mpm_solver.hpp"

namespace pbms::mpm {

// One entry of the stage's probe list.
struct ProbeSpec {
  std::string name;
  std::string kind;
  std::optional<std::string> group;
  std::string axis;  // group_extent: x, y or z

  static ProbeSpec from_yaml(const YAML::Node& probe);
  static std::vector<ProbeSpec> list_from_yaml(const YAML::Node& probes);
};

class MpmProbes {
 public:
  // Group names are checked against the model. Records the groups'
  // starting centres of mass.
  MpmProbes(const std::vector<ProbeSpec>& probes, const MpmModel& model, bool metal_units);

  // Column names and units, in the order of values().
  [[nodiscard]] const std::vector<std::string>& columns() const { return columns_; }
  [[nodiscard]] const std::vector<std::string>& units() const { return units_; }

  // Local partial sums and maxima of this rank's points.
  void local(const grid::MaterialPoints& points, const grid::MpmSolver& solver,
             const grid::BoundaryConditions& bc, std::vector<double>& sums,
             std::vector<double>& maxima) const;
  // Column values from the reduced sums and maxima.
  [[nodiscard]] std::vector<double> values(const std::vector<double>& sums,
                                           const std::vector<double>& maxima) const;
  // The starting centres of mass need one reduced sample at step 0.
  void set_reference(const std::vector<double>& values);
  [[nodiscard]] const std::vector<double>& reference() const { return reference_; }

  [[nodiscard]] bool has_energy() const { return energy_column_ >= 0; }
  [[nodiscard]] int energy_total_column() const { return energy_column_; }

 private:
  struct Probe {
    std::string name, kind;
    uint32_t mask = 0;
    size_t axis = 0;
    size_t sum_offset = 0, max_offset = 0, column = 0;
    int point_velocity = -1;  // group_force: the bc.point_velocities entry
  };
  std::vector<Probe> probes_;
  std::vector<std::string> columns_, units_;
  size_t n_sums_ = 0, n_max_ = 0;
  std::vector<double> reference_;
  int energy_column_ = -1;
};

}  // namespace pbms::mpm
