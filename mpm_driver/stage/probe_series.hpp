// The probes' columns over an mpm_run: each sample reduces the probes'
// rank-local sums and maxima over the engine's ranks (one call each) and
// appends a row; report() turns the table into results, with the energy
// drift and the oscillation period where asked for.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/mpm_engine.hpp"
#include "mpm_probes.hpp"
#include "mpm_run_params.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::mpm {

class ProbeSeries {
 public:
  ProbeSeries(const std::vector<ProbeSpec>& probes, const MpmModel& model, bool metal_units);

  // Collective. The sample at step 0 also fixes the probes' references.
  void sample(const MpmEngine& engine, std::int64_t step, double t);
  void report(StageResults& r, const MpmRunParams& params, const std::string& stage) const;
  // The samples and references, for a checkpoint; and back.
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  MpmProbes probes_;
  std::vector<std::vector<double>> columns_;
  std::vector<double> step_, time_;
  std::vector<double> sums_, maxima_, reduced_sums_, reduced_max_;
};

}  // namespace pbms::mpm
