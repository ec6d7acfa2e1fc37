// The parameters of a concurrent DPD/MPM stage that both of its parts
// read (dpd_driver's `concurrent` and mpm_driver's part of it), turned once
// into a typed struct from the validated stage map. The DPD part also
// reads the body (bodies or initial state, groups, motion) the way every
// dpd stage does.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/coupling/coupling_side.hpp"
#include "pbms/coupling/neck_spec.hpp"
#include "pbms/geometry/region.hpp"
#include "pbms/grid/regular_grid.hpp"

namespace pbms::coupling {

enum class Solver { kDpd, kMpm };

// Whether box `inner` lies within `outer` and is not the same box: a
// region nested in another, whose solver wins inside it.
[[nodiscard]] bool nests_in(const geometry::Box& inner, const geometry::Box& outer);

struct ConcurrentRegion {
  std::string name;
  Solver solver = Solver::kDpd;
  std::shared_ptr<const geometry::Region> region;
};

// A wave speed between two slabs (groups) of one solver's particles.
struct SpeedProbe {
  std::string name;
  std::string near_slab, far_slab;
};

// A tension test between two rigid grips (groups held at their velocity):
// stress is the grips' holding force over the body's initial cross-section,
// strain their separation's change over the body's initial length.
struct TensionProbe {
  std::string left_grip, right_grip;
  int axis = 0;
  double fit_strain = 0.0;  // upper end of the linear fit for E
};

// A group held at a velocity (motion kind rigid, or frozen at rest): on the
// MPM part, the grip's points are prescribed as an MPM grip is.
struct HeldGroup {
  std::string group;
  Vec3 velocity{0.0, 0.0, 0.0};
  double ramp_time = 0.0;  // ps: `velocity` reached over this time (velocity_ramp.hpp)
};

// Ideal-gas MPM points around the body (seed chapter 6), all in solver
// units: Å, g/mol/Å³, bar, ps.
struct GasParams {
  double spacing = 0.0;     // simple cubic lattice edge
  geometry::Vec3 origin{};  // one site of the lattice
  double density = 0.0;     // g/mol/Å³
  double pressure = 0.0;    // bar: the target
  double gamma = 1.4;
  double flip = 0.95;                       // the gas points' own FLIP/PIC blend
  bool density_from_grid = true;            // else integrated along each point's path
  double density_time = 2.0;                // ps: the points' density relaxes to the grid's over it
  double heat_bath_time = 1.0;              // ps: e relaxes to its start over it; 0: adiabatic
  double ramp_time = 0.0;                   // ps: the heat bath's target rises from 0 over it
  double clearance = 0.0;                   // sites nearer a body particle stay empty
  double probe_distance = 0.0;              // the pressure is measured this far from the body
  double settle_time = 0.0;                 // ps: gas_pressure averages the samples from here on
  bool walls = true;                        // the non-periodic faces hold no normal velocity
  GridFields fields = GridFields::kShared;  // how gas and body move at shared nodes

  [[nodiscard]] double point_volume() const { return spacing * spacing * spacing; }
  [[nodiscard]] double point_mass() const { return density * point_volume(); }
};

// A block's volume from its three edges (the `volume` probe).
struct VolumeProbe {
  std::string group;
  std::optional<double> reference;  // Å³: V0, else the volume at the start
};

// A rod whose bend is followed (the `rods` probe).
struct RodBend {
  std::string name;
  std::string group;
  int axis = 2;
};

struct ConcurrentParams {
  grid::RegularGrid grid{{0.0, 0.0, 0.0}, 1.0, {1, 1, 1}};
  std::array<bool, 3> periodic{false, false, false};
  double flip = 1.0;
  // How both programs move their particles and points (grid.move).
  grid::PointMove move = grid::PointMove::kStepStart;
  // Extra reach of the interface band beyond the cells the two bodies
  // touch, Å: how far particles may travel from where they start.
  double band_margin = 0.0;
  std::vector<ConcurrentRegion> regions;
  InterfaceTreatment interface = InterfaceTreatment::kSeed;
  // The momentum-conserving interface's ghost forces, measured over this
  // many steps and subtracted from then on (ghost_force_correction.hpp);
  // 0: not corrected.
  std::int64_t ghost_force_steps = 0;
  std::string ghost_force_stage;  // else: the dead loads this earlier stage measured
  // The body starts uniformly strained along each axis (positions scaled
  // about the box's lower corner), its MPM points carrying the stress of
  // that strain.
  std::array<double, 3> initial_strain{0.0, 0.0, 0.0};
  double youngs_modulus = 0.0;  // bar; 0 without a continuum (no MPM region)
  double poisson_ratio = 0.0;
  bool ddmp = false;  // the MPM points' gradients
  // The DPD crystal's lattice constant at the run's temperature (each MPM
  // point's volume is a³/4), when given; else the material's.
  std::optional<double> lattice_constant;
  std::string material;        // the stage's dpd_mesoparticle material
  double particle_mass = 0.0;  // g/mol: the material's mesoparticle, and so each MPM point
  double material_lattice_constant = 0.0;  // Å: the material's
  std::string interface_name;              // as written: none, seed, momentum_conserving
  std::vector<HeldGroup> held;
  double time_step = 0.0;  // ps
  std::int64_t steps = 0, sample_every = 1, particles_every = 0, profile_every = 0;
  int axis = 0;             // of the wave and the interface opening
  double threshold = 0.0;   // Å, a slab's first motion
  double smoothing = 0.05;  // ps, mid-amplitude arrival: the velocity's running mean
  double window = 0.1;      // ps, mid-amplitude arrival: the top's distance from first motion
  std::vector<SpeedProbe> speeds;
  // wave.baseline: per side ("dpd", "mpm"), the slab histories of an
  // earlier stage of the same body and start that was not struck, column by
  // column (time and one per slab); subtracted before any arrival is timed.
  std::map<std::string, std::map<std::string, std::vector<double>>> baseline;
  // The earlier stage whose noise stream the DPD part draws (its name
  // mixed with the run seed), so that a stage and its baseline share it.
  std::optional<std::string> noise_of;
  // The lattice planes on either side of the interface (groups), whose
  // displacement jump is the interface opening.
  std::optional<std::pair<std::string, std::string>> opening;  // dpd plane, mpm plane
  std::optional<TensionProbe> tension;
  std::optional<GasParams> gas;
  [[nodiscard]] GridFields fields() const { return gas ? gas->fields : GridFields::kShared; }
  // Berendsen rescaling of the DPD part about its mean velocity: K, ps.
  std::optional<std::pair<double, double>> thermostat;
  std::optional<VolumeProbe> volume;
  std::vector<NeckPair> necks;
  double neck_stable_time = 20.0;  // ps: neck_width_<name> averages the last this much
  std::vector<RodBend> rods;

  // Reads a `concurrent` stage's validated parameters (metal units) and
  // its dpd_mesoparticle material.
  static ConcurrentParams from_yaml(const YAML::Node& params, const YAML::Node& material);

  // Each MPM point's lattice constant (its volume is a³/4): the continuum's,
  // or the material's.
  [[nodiscard]] double point_lattice_constant() const {
    return lattice_constant.value_or(material_lattice_constant);
  }
  // The solver of a particle at x: the innermost region holding it (regions
  // may nest: a core inside a shell), else the first; DPD when none does (a
  // flyer outside the body's regions).
  [[nodiscard]] Solver solver_at(const geometry::Vec3& x) const;
  // That region's index in `regions`; -1 where none holds x.
  [[nodiscard]] int region_at(const geometry::Vec3& x) const;
  // Which part of the body a solver advances, for messages: "the MPM part
  // (region 'right')".
  [[nodiscard]] std::string part(Solver s) const;
};

}  // namespace pbms::coupling
