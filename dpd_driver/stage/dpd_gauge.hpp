// The gauge reading of a DPD tension run (analysis::GaugeSection): the
// Cauchy stress of a section in the rod's middle, from the forces across
// its material planes, and the section's own strain. The rod's virial
// measure counts the grips and the starting cross-section; the gauge reads
// what a continuum material calibrated from the rod should reproduce.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "engine/dpd_engine.hpp"
#include "pbms/analysis/tension_test.hpp"
#include "pbms/io/checkpoint_archive.hpp"
#include "pbms/results.hpp"

namespace pbms::dpd {

class DpdGauge {
 public:
  // `all` is the full starting set of particles (every rank holds it before
  // the engine splits it): their axial coordinates fix the gauge's members.
  // `plane` is the lattice plane spacing added to lateral extents, as the
  // rod measure adds it to its length.
  DpdGauge(const analysis::GaugeSection& gauge, const DpdParticles& all, std::uint32_t specimen,
           int axis, double plane);

  // The cross-section at the first sample, Å^2: the rod's nominal one (its
  // sites' volume over its length) or the user's `area`. The section then
  // follows the gauge's lateral extents in proportion. The extents alone
  // would count the outermost sites' thermal excursions, about 0.8 Å of
  // width at 298 K: 2 % of a 10 x 10 a_cg rod's area (docs/hierarchy.md).
  void set_starting_area(double area) { area0_ = area; }
  // Collective: one sample of the gauge's strain and stress, from the
  // forces of the last step.
  void sample(const DpdEngine& engine);
  void report(const analysis::TensionTest& test, StageResults& r, const std::string& stage) const;
  void save(CheckpointArchive& a) const;
  void load(const CheckpointArchive& a);

 private:
  analysis::GaugeSection gauge_;
  std::unordered_map<std::int64_t, double> start_;  // id -> starting axial coordinate
  std::uint32_t specimen_ = 0;
  int axis_ = 0;
  double plane_ = 0.0;
  double distance0_ = 0.0;
  double area0_ = 0.0;     // the cross-section at the first sample, Å^2
  double extents0_ = 0.0;  // the lateral extents' product at the first sample, Å^2
  std::vector<double> strain_, stress_;
};

}  // namespace pbms::dpd
