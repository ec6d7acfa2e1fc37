// What every DPD stage that builds a body takes (dpd_run, dpd_equilibrate,
// and the DPD part of a concurrent stage): the box, lattice-filled bodies or
// an earlier state, groups and their motion, the integrator, probes and
// output. Declared once (dpd_stage_params) and read once into
// DpdStageParams; with the stage's dpd_mesoparticle material
// (MesoparticleMaterial), build_dpd_model turns them into particles.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "kernels/orthogonal_box.hpp"
#include "pbms/config/axis_name.hpp"
#include "pbms/config/param.hpp"
#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/geometry/region.hpp"

namespace pbms::dpd {

// The schema of the keys below.
[[nodiscard]] std::vector<config::Param> dpd_stage_params();

// A dpd_mesoparticle material, resolved (potential files read).
struct MesoparticleMaterial {
  double mass = 0.0;              // g/mol, one mesoparticle
  double lattice_constant = 0.0;  // Å, of its fcc crystal
  YAML::Node potential;           // the pair style's map (pair_style_from_yaml)
  double atoms_per_particle = 8;  // volumes per atom (isotherms, the fit) divide by it

  // The dpd_mesoparticle material kind: these keys, and the potential's
  // (each pair style's own, PairStyleRegistry::schema).
  static config::MaterialKindSpec spec();
  static MesoparticleMaterial from_yaml(const YAML::Node& material);
};

struct DpdProbeSpec {
  std::string name;
  std::string kind;   // temperature, pressure, energy, momentum, slab_displacement, ...
  std::string group;  // the group probes
  int axis = 0;       // group_extent
};

struct DpdStageParams {
  std::string material;
  OrthogonalBox box;
  // `initial`: how many of its keys are given, and each one's value.
  struct Piece {
    std::string from_stage;
    Vec3 shift{0.0, 0.0, 0.0};
  };
  struct Initial {
    std::size_t keys = 0;
    std::string from_stage, h5md, lammps_data;
    std::vector<Piece> pieces;
  };
  std::optional<Initial> initial;
  struct Body {
    std::string name;
    std::shared_ptr<const geometry::Region> region;
    Vec3 lattice_origin{0.0, 0.0, 0.0};
  };
  std::vector<Body> bodies;
  struct Group {
    std::string name;
    std::shared_ptr<const geometry::Region> region;
  };
  std::vector<Group> groups;
  struct Motion {
    std::string group;
    std::string kind;  // rigid, rigid_body, frozen, velocity
    Vec3 velocity{0.0, 0.0, 0.0};
    double ramp_time = 0.0;  // rigid
  };
  std::vector<Motion> motion;
  double temperature = 0.0;
  std::string scheme;
  double gamma = 0.0, dpd_cutoff = 0.0;
  std::string noise;
  std::optional<double> bath_temperature;
  double heat_capacity = 0.0;  // in k_B
  // The DPD/MPM-grid model (`grid`); a concurrent stage's grid has more keys.
  struct Grid {
    double cell_size = 0.0;
    double flip = 1.0;
    bool midpoint_move = true;  // grid.move: midpoint, or step_start
  };
  std::optional<Grid> grid;
  double time_step = 0.0;
  std::int64_t steps = 0;
  double skin = 0.0;
  std::int64_t sample_every = 1;
  std::vector<DpdProbeSpec> probes;
  std::int64_t particles_every = 0;
  bool write_forces = false, write_internal_energy = false;

  static DpdStageParams from_yaml(const YAML::Node& params);
};

// "x", "y", "z" as 0, 1, 2.
using config::axis_index;

}  // namespace pbms::dpd
