// The hand-fitted Morse potential of the copper mesoparticle
// (docs/dpd-morse-fit.md), read from configs/potentials/cu_cg_morse.yaml so
// that a refit edits that file alone. The file goes through the same schema
// check and pair_style_from_yaml as a workflow's `potential_file`, so the
// unit tests and bench/dpd_morse_bench run the style users get from it.
// Needs PBMS_SOURCE_DIR (the source tree, set by CMake) and pbms_dpd.
#pragma once

#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include "kernels/pair_style.hpp"
#include "kernels/pair_style_registry.hpp"
#include "pbms/config/validator.hpp"
#include "pbms/config/workflow.hpp"
#include "pbms/error.hpp"
#include "stage/dpd_model.hpp"

namespace pbms::dpd {

inline const std::string kCuCgMorseFile = PBMS_SOURCE_DIR "/configs/potentials/cu_cg_morse.yaml";

// The file's `potential` map as the schema resolves it (defaults filled in,
// quantities in metal units). Throws pbms::Error listing every problem.
inline YAML::Node cu_cg_morse_yaml() {
  config::Validator validator(kCuCgMorseFile);
  YAML::Node potential;
  try {
    potential = validator.check(dpd::PairStyleRegistry::schema(), YAML::LoadFile(kCuCgMorseFile),
                                "potential");
  } catch (const YAML::Exception& e) {
    throw Error(kCuCgMorseFile + ": " + e.what());
  }
  if (!validator.errors().empty()) {
    std::string message;
    for (const auto& error : validator.errors()) message += error.format() + "\n";
    throw Error(message);
  }
  return potential;
}

// The numbers themselves, for what cannot take a PairStyle: LAMMPS inputs.
struct CuCgMorseParameters {
  double d0;      // eV
  double alpha;   // 1/Å
  double r0;      // Å
  double cutoff;  // Å
  bool shift;     // energies shifted to zero at the cutoff
};

inline CuCgMorseParameters cu_cg_morse_parameters() {
  const YAML::Node p = cu_cg_morse_yaml();
  return {p["d0"].as<double>(), p["alpha"].as<double>(), p["r0"].as<double>(),
          p["cutoff"].as<double>(), p["shift"].as<bool>()};
}

inline std::unique_ptr<PairStyle> cu_cg_morse() {
  return pair_style_from_yaml(cu_cg_morse_yaml());
}

}  // namespace pbms::dpd
