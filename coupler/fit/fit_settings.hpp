// The input of a fit_dpd_potential stage: its schema (declared beside the
// kind, published through `coupler describe`), the checks the schema cannot
// express, and the typed settings read once from the resolved YAML.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/config/crystal_sampling.hpp"
#include "pbms/config/param.hpp"
#include "pbms/config/stage_kind_spec.hpp"

namespace pbms::coupler::fit {

struct FreeParameter {
  std::string name;  // a key of the potential's style: "d0", "alpha"
  double lower = 0.0, upper = 0.0;
  double start = 0.0;  // the material's value
};

// The MD isotherm: volume per atom (Å^3) at each pressure (bar).
struct IsothermTarget {
  std::vector<double> pressure;
  std::vector<double> volume_per_atom;
  std::vector<bool> held_out;
  double weight = 1.0;
};

// Elastic constants in bar; a constant not given is not a target.
struct ElasticTarget {
  std::optional<double> c11, c12, c44;
  double weight = 1.0;
};

// The static (100) surface energy of the crystal (eV/Å^2). Bulk targets
// leave a weak direction of the parameters along which the surface energy
// of the mesoparticle crystal changes more than twofold (seeds 2026-2029 of
// configs/hierarchy.yaml: 2.0 to 5.1 J/m^2), and a thin rod feels it.
struct SurfaceTarget {
  double energy_100 = 0.0;
  double weight = 1.0;
};

struct OptimizerSettings {
  std::string global = "crs2_lm";  // crs2_lm | direct_l | none
  std::string local = "bobyqa";    // bobyqa | sbplx | levenberg_marquardt | none
  int global_evaluations = 60;
  int local_evaluations = 60;
  double x_tolerance = 1e-4;  // relative, in the unit box of the bounds
  double f_tolerance = 1e-10;
  bool static_prefit = false;  // global search on the static (0 K) crystal
  bool log_scale = false;      // search in ln(parameter) between ln(bounds)
};

// What every judging request shares besides the candidate's potential.
// The candidates' crystal: at the targets' temperature, sampled as the
// `judge` map says (dpd_driver's properties stages take the same keys).
struct JudgeSettings {
  double temperature = 298.0;
  config::CrystalSampling sampling;
  // The judge's runs' seed; the run's when unset. Targets that the DPD
  // engine computed at the run's seed share its noise with the judge at
  // that seed, so another seed is how a test sees the parameters' spread.
  std::optional<std::uint64_t> seed;
};

struct FitSettings {
  std::string material;
  YAML::Node start_potential;          // the material's potential map
  std::string style;                   // its pair style
  std::optional<double> start_cutoff;  // Å, where its style has one
  std::vector<FreeParameter> free;
  std::optional<IsothermTarget> isotherm;
  std::optional<ElasticTarget> elastic;
  std::optional<SurfaceTarget> surface;
  OptimizerSettings optimizer;
  JudgeSettings judge;
  int group_ranks = 1;
  int atoms_per_particle = 8;

  // From the resolved stage (references to tables replaced by tables) and
  // the resolved materials. Throws pbms::Error for what only the run can
  // see (a table without the columns a target needs).
  static FitSettings from_yaml(const YAML::Node& stage, const YAML::Node& materials);
};

config::StageKindSpec fit_dpd_potential_spec();

// The pair styles' schema (dpd_mesoparticle's `potential`, which dpd_driver
// declares), or null when no driver declares it.
[[nodiscard]] const config::Param* potential_schema(
    const std::vector<config::DriverDescription>& drivers);

// A sharp cutoff makes P(V) jump where a neighbour shell of the fcc crystal
// crosses it. Throws pbms::Error naming the shell if `cutoff` lies within
// `margin` (relative, for thermal spread) of a shell distance anywhere over
// the target volumes per atom [v_min, v_max].
void check_cutoff_between_shells(double cutoff, double v_min, double v_max, int atoms_per_particle,
                                 double margin = 0.02);

// Every second point of a ladder of n, starting with the second.
std::vector<bool> default_held_out(size_t n);

}  // namespace pbms::coupler::fit
