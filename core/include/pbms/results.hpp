// What a stage produces: scalar results (they go to summary.yaml and may be
// referenced by later stages) and tables of named columns (they go to
// results.h5 and plots). Units are metal units unless a key says otherwise
// (moduli are reported in GPa, as users quote them).
#pragma once

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pbms/protocol/wire.hpp"

namespace pbms {

struct ScalarResult {
  std::string key;
  double value = 0.0;
  std::string unit;
  double std_error = std::nan("");  // NaN when not estimated
  PBMS_FIELDS(key, value, unit, std_error)
};

struct Column {
  std::string table;  // "isotherm": becomes an HDF5 group inside the stage group
  std::string name;   // "pressure"
  std::string unit;
  std::vector<double> data;
  PBMS_FIELDS(table, name, unit, data)
};

struct StageResults {
  std::vector<ScalarResult> scalars;
  std::vector<Column> columns;
  std::vector<std::string> files;                 // written by the driver, relative to the run dir
  std::map<std::string, std::string> attributes;  // free text: "lammps_version", ...
  // A result that is computed but probably meaningless (a modulus fitted to
  // a pull that barely started): shown in the run's last lines and report.
  std::vector<std::string> warnings;
  PBMS_FIELDS(scalars, columns, files, attributes, warnings)

  void add_scalar(std::string key, double value, std::string unit,
                  double std_error = std::nan("")) {
    scalars.push_back({std::move(key), value, std::move(unit), std_error});
  }
  void add_warning(std::string message) { warnings.push_back(std::move(message)); }
  void add_column(std::string table, std::string name, std::string unit, std::vector<double> data) {
    columns.push_back({std::move(table), std::move(name), std::move(unit), std::move(data)});
  }
  [[nodiscard]] std::optional<double> scalar(const std::string& key) const {
    for (const auto& s : scalars) {
      if (s.key == key) return s.value;
    }
    return std::nullopt;
  }
};

}  // namespace pbms
