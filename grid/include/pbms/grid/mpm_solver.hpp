// One explicit MPM time step on a regular background grid (Sulsky, Chen &
// Schreyer 1994; seed §2.4.2 steps s-1 to s-14), with update-stress-last or
// -first, a FLIP/PIC blend and plain or DDMP (dual-domain) gradients.
// Physics only: no MPI, no files. A decomposed run gives each rank's solver
// its box of the grid and a function that completes shared-node sums.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pbms/grid/boundary_conditions.hpp"
#include "pbms/grid/ddmp_gradient.hpp"
#include "pbms/grid/material.hpp"
#include "pbms/grid/material_block.hpp"
#include "pbms/grid/material_points.hpp"
#include "pbms/grid/node_lanes.hpp"
#include "pbms/grid/regular_grid.hpp"
#include "pbms/grid/shape_function.hpp"
#include "pbms/grid/shape_function_linear.hpp"
#include "pbms/simd/point_lanes.hpp"

namespace pbms::grid {

enum class StressUpdate { kLast, kFirst };

// The grid velocity a point moves with (update-stress-last).
// kStepStart: the updated nodal velocity at the positions the step started
// from (MUSL, as CB-Geo's scheme and the seed move). Where points share
// nodes its position update is first order, and particles lose energy by
// it (docs/dpd-driver.md: 3.6 of 9.8 eV in 10 ps at h = a/2).
// kMidpoint: the points' new momentum mapped back to the grid at a midpoint
// that half that move predicts, the move made from the step's start: a
// time-symmetric move to second order, with which a crystal of particles
// sharing nodes keeps its energy as velocity Verlet does. One more grid
// pass and halo sum a step; the solver must complete its nodal sums itself,
// so a run whose nodes another program also sums cannot take it.
enum class PointMove { kStepStart, kMidpoint };

// SolverOptions::contact. The normal comes from one field's mass gradient,
// the same on both sides: that of the field whose points fill space evenly.
// A DPD body on cells of a_cg/2 holds half a particle per cell; its mass
// gradient points at the nearest particle rather than out of its surface,
// and through that noise a gas flooded two copper spheres (1,285 gas points
// more than 5 Å inside them after 20 ps at 3 GPa) where the gas's lattice,
// one point per cell, let none in.
enum class ContactField {
  kNone,
  kSurfaceFromOwnMass,    // this field's mass gives the normal (the gas)
  kSurfaceFromOtherMass,  // the other field's does (the body in a gas)
};

// Conversion factors between the stress, force and acceleration units of a
// run: 1 for consistent units (the seed's 1-D bar), metal units otherwise.
struct UnitSystem {
  double stress_volume_to_energy = 1.0;  // sigma * V -> energy (bar Å^3 -> eV)
  double force_per_mass_to_accel = 1.0;  // f / m -> acceleration (eV/Å/(g/mol) -> Å/ps^2)
  static UnitSystem metal();
};

struct SolverOptions {
  StressUpdate stress_update = StressUpdate::kLast;
  PointMove move = PointMove::kStepStart;
  // Whether these points are one velocity field of a frictionless contact
  // with another program's, which shares the grid's nodes without sharing
  // their velocity (frictionless_contact.hpp: a gas around a body), and
  // whose mass gives the surface normal. map_to_grid then also maps this
  // field's mass gradient; the other field's records (contact_fields) must
  // be filled before update_nodes, and its remapped momentum before
  // update_stress_and_move. Update-stress-last and the step-start move only.
  ContactField contact = ContactField::kNone;
  double flip = 1.0;  // 1: FLIP, 0: PIC
  // A material's own FLIP/PIC blend on top of `flip`, by material index (1,
  // the default, adds nothing): an inviscid gas at one point per cell needs some PIC, which
  // damps the velocity modes the grid cannot see (FLIP's null space). Taken
  // towards the material's own nodal field, so that its momentum is kept
  // (MpmSolver::relax_to_own_field).
  std::vector<double> material_flip;
  [[nodiscard]] double flip_of(int material) const {
    const auto m = static_cast<std::size_t>(material);
    return m < material_flip.size() ? material_flip[m] : 1.0;
  }
  // Materials (by index, nonzero) whose points take their density from the
  // grid each step: the material's nodal mass over the nodal volume the
  // rest of the nodes' mass does not fill, at `filler_density` (g/mol/Å³ in
  // metal units: the body's). A gas at one point per cell whose density is
  // only integrated along each point's path drifts from the space its points
  // fill; this ties it to where they are (MpmSolver::own_material_fields).
  std::vector<char> material_density_from_grid;
  double filler_density = 0.0;
  // The part of the way to the grid's density a point goes each step (dt
  // over a relaxation time): 1 takes it whole. The grid's density is of the
  // step's start and acts on the next step's forces; taken whole, that lag
  // pumps energy into the gas's sound (at 5 GPa its kinetic energy grew 50
  // times in 20 ps). Taken slowly, the points' own integration carries the
  // sound and the grid only corrects the drift.
  double grid_density_weight = 1.0;
  [[nodiscard]] bool density_from_grid(int material) const {
    const auto m = static_cast<std::size_t>(material);
    return m < material_density_from_grid.size() && material_density_from_grid[m] != 0;
  }
  // Blend weight alpha of the plain gradient: 1 is plain MPM, 0 pure DDMP;
  // "face_vanishing" uses 4 xi (1 - xi) per axis (seed Appendix 2).
  bool ddmp = false;
  bool ddmp_face_vanishing = false;
  // Nodes lighter than this fraction of the lightest point's mass are left
  // out of the divisions (end of seed §2.4.2): their velocity would be noise.
  double small_mass_fraction = 1e-3;
  // The lightest point's mass over all ranks; 0 takes the lightest local
  // point, which is only right for a serial run.
  double reference_point_mass = 0.0;
  UnitSystem units;
  // What a failure calls a point (the DPD/MPM-grid step's are particles),
  // and, by material index where given, a material's ("gas point").
  std::string point_noun = "material point";
  std::vector<std::string> material_nouns;
  [[nodiscard]] const std::string& noun_of(int material) const {
    const auto m = static_cast<std::size_t>(material);
    return m < material_nouns.size() && !material_nouns[m].empty() ? material_nouns[m] : point_noun;
  }
};

// The part of the grid one solver works on.
struct GridPatch {
  RegularGrid domain;  // the whole grid
  NodeBox nodes;       // this solver's nodes, in the domain's indices
  std::array<bool, 3> periodic{false, false, false};
  // Adds the parts other boxes (or periodic images) hold to the shared
  // nodes: `components` values per node, `stride` doubles apart. Empty when
  // nothing is shared.
  std::function<void(double* data, int components, int stride)> sum_shared;

  static GridPatch whole(const RegularGrid& g) { return {g, g.node_box(), {}, {}}; }
};

// Energies of a set of points. `stored` and `dissipated` come from the
// material's state; `work` is the stress work done on the points since the
// start, which for a rate-form model at finite strain is the internal
// energy that balances the kinetic energy (its stored-energy estimate from
// the current stress is exact only at small strain).
struct EnergySummary {
  double kinetic = 0.0;
  double stored = 0.0;
  double dissipated = 0.0;
  double work = 0.0;
  [[nodiscard]] double total() const { return kinetic + stored + dissipated; }
};

class MpmSolver {
 public:
  MpmSolver(GridPatch patch, std::unique_ptr<ShapeFunction> shape,
            std::vector<std::unique_ptr<Material>> materials, SolverOptions options);
  // A serial solver on the whole grid.
  MpmSolver(const RegularGrid& grid, std::unique_ptr<ShapeFunction> shape,
            std::vector<std::unique_ptr<Material>> materials, SolverOptions options)
      : MpmSolver(GridPatch::whole(grid), std::move(shape), std::move(materials),
                  std::move(options)) {}

  // Advances the points by dt: the phases below, in order. Points end
  // wrapped on periodic axes and may have left this solver's box (the
  // caller migrates them). Throws pbms::Error naming the point (id,
  // position) if one leaves the grid.
  void step(MaterialPoints& points, const BoundaryConditions& bc, double dt);

  // The phases of one step, for a coupling scheme that adds another
  // program's part of the nodal sums between them (the order of CB-Geo
  // mpm's explicit scheme). Each must follow the one before it; a phase
  // out of order throws pbms::Error. Between map_to_grid and update_nodes
  // nodal_sums() holds mass, momentum and force; between map_to_points and
  // update_stress_and_move it holds the remapped momentum.
  void begin_step(const MaterialPoints& points);  // mass floor, DDMP operator
  // s-1 to s-4 from this solver's points (update-stress-first also updates
  // the stress first, summing over this solver's ranks on its own).
  void map_to_grid(MaterialPoints& points, const BoundaryConditions& bc, double dt);
  void complete_nodal_sums();  // over this solver's ranks (GridPatch::sum_shared)
  // s-5, s-6 and the essential and rigid-group conditions.
  void update_nodes(const BoundaryConditions& bc, double dt);
  // s-7 for the point velocities, and the remap of their momenta (s-10);
  // under update-stress-first, the move (s-8).
  void map_to_points(MaterialPoints& points, const BoundaryConditions& bc, double dt);
  void complete_remap_sums();  // over this solver's ranks
  // s-11 to s-14 and the move (s-8), update-stress-last: the three below
  // in one.
  void update_stress_and_move(MaterialPoints& points, const BoundaryConditions& bc, double dt);
  // The same in three, for a coupling scheme whose other program's points
  // also move from their midpoints (PointMove::kMidpoint): the stress
  // update and, with the midpoint move, half a move and the map of the
  // points' mass and momentum at their midpoints; the sums of that map
  // over this solver's ranks (another program's part is added after it);
  // the move from the start with the grid velocity at the midpoint. With
  // the step-start move the first does it all and the others do nothing.
  void update_stress_and_map_midpoints(MaterialPoints& points, const BoundaryConditions& bc,
                                       double dt);
  void complete_midpoint_sums();
  void move_from_midpoints(MaterialPoints& points, const BoundaryConditions& bc, double dt);

  // The nodal sums of this solver's patch, `stride` doubles per node in
  // patch().nodes' local order: lane 0 mass, 1-3 momentum, 4-6 force
  // (node_lanes.hpp).
  struct NodalSums {
    double* data;
    int stride;
    NodeBox nodes;
  };
  [[nodiscard]] NodalSums nodal_sums();

  // SolverOptions::contact: this field's mass gradient (3 doubles per node,
  // complete after complete_nodal_sums), and the other field's records as
  // a link fills them: its sums (nodal_sums' lanes; zero where it has
  // none) and its mass gradient, over patch().nodes.
  struct ContactFields {
    NodalSums gradient;
    NodalSums other_sums;
    NodalSums other_gradient;
  };
  [[nodiscard]] ContactFields contact_fields();

  // The largest stable time step over these points: h / max_p (c_p + |v_p|).
  [[nodiscard]] double stable_time_step(const MaterialPoints& points) const;
  [[nodiscard]] EnergySummary energy(const MaterialPoints& points) const;
  // Force (eV/Å, over the nodes this rank counts) that held each
  // bc.point_velocities entry's nodes at its prescribed velocity in the
  // last step: the reaction a rigid grip, piston or flyer feels.
  [[nodiscard]] const std::vector<Vec3>& point_velocity_reactions() const { return reaction_; }
  // The momentum the node constraints (walls) gave this rank's nodes in the
  // last step, each node on one rank only (g/mol Å/ps in metal units).
  [[nodiscard]] const Vec3& node_constraint_impulse() const { return constraint_impulse_; }
  // Of that, what the constraints on the grid's outer node planes gave
  // along their inward normals, summed (g/mol Å/ps): over a time and the
  // faces' area, the pressure a material pressed on those walls.
  [[nodiscard]] double outer_face_push() const { return outer_face_push_; }
  // Between update_nodes and map_to_points: the mass on entry c's held
  // nodes (over the nodes this rank counts), and a change dv of those
  // nodes' velocity on the axes it holds (every copy; the caller changes
  // the entry's velocity alike). A free rigid body takes them to balance
  // its reaction: the velocity that makes it zero conserves momentum
  // (DpdGridStep). Nodes another entry also holds are shifted too, so the
  // balance is exact only for a body whose nodes no other entry holds.
  [[nodiscard]] double held_mass(size_t c) const;
  // Entry c's points' share of each node's mass times the node's velocity
  // before the update, summed over this rank's nodes: what FLIP would give
  // those points' momentum before the hold sets it (DpdGridStep).
  [[nodiscard]] const Vec3& held_share_momentum(size_t c) const { return share_momentum_[c]; }
  void shift_held_nodes(const BoundaryConditions& bc, size_t c, const Vec3& dv, double dt);

  // Holds across programs (a concurrent run, whose two programs map to the
  // nodes they share): each must hold the nodes the other's rigid groups
  // hold, or its material there moves freely while the other's is held.
  // Between update_nodes and map_to_points, `records` gets, per node of
  // patch().nodes, kHeldStride doubles: the axes this solver holds there,
  // as a sum of 1 (x), 2 (y) and 4 (z), then the held velocity on those
  // axes (0 on the others), after any shift_held_nodes.
  static constexpr int kHeldStride = 4;
  void held_nodes(const BoundaryConditions& bc, double* records) const;
  // After complete_nodal_sums: lane sums::kHeldAxes of each node's sums
  // gets the axes held there (as in held_nodes), so that a sum across
  // programs tells both whether either holds a node they share.
  void mark_held_nodes(const BoundaryConditions& bc);
  // Holds the nodes another program holds (records as held_nodes writes
  // them) at its velocities: now, and on the remapped velocities of s-11,
  // as this solver's own groups are held. Their force is the other
  // program's reaction, not added to this solver's.
  void hold_nodes_of_others(const double* records, double dt);

  [[nodiscard]] const RegularGrid& grid() const { return patch_.domain; }
  [[nodiscard]] const GridPatch& patch() const { return patch_; }
  [[nodiscard]] const Material& material(int i) const {
    return *materials_[static_cast<size_t>(i)];
  }
  [[nodiscard]] size_t material_count() const { return materials_.size(); }
  // Nodal fields after the last step, over patch().nodes (for grid output):
  // mass and the velocity of the momentum update (s-6).
  [[nodiscard]] double nodal_mass(size_t local) const { return sums_[local].lanes[sums::kMass]; }
  [[nodiscard]] const Vec3& nodal_velocity(size_t local) const { return velocity_[local]; }
  // The grid velocity the points last moved with at a node: the remap's,
  // or with PointMove::kMidpoint the midpoints'.
  [[nodiscard]] const Vec3& move_velocity(size_t local) const { return remap_velocity_[local]; }
  // Internal plus external nodal force of the last step, eV/Å.
  [[nodiscard]] const Vec3& nodal_force(size_t local) const { return node_force_[local]; }

  // Points the linear passes take at once, one per SIMD lane: the width of
  // the instruction set this build targets (simd/point_lanes.hpp).
  static constexpr int kLanes = simd::kPointLanes;
  // kLanes and its instruction set as compiled into the solver itself, for
  // a bench or test that links a variant built for another set.
  struct SimdWidth {
    int lanes;
    const char* isa;
  };
  static SimdWidth simd_width();

 private:
  using PointLanes = simd::Lanes<kLanes>;
  enum class Phase {
    kBegin,
    kMapToGrid,
    kCompleteNodalSums,
    kUpdateNodes,
    kMapToPoints,
    kCompleteRemapSums,
    kUpdateStress
  };
  // Checks that `next` is the phase due and moves on to the one after it.
  void enter(Phase next);
  // Runs a particle pass with a shape-function evaluator: an inlined one
  // for the linear style, the generic virtual one otherwise.
  template <class F>
  void with_eval(F&& pass);
  template <class Eval>
  void grid_to_points(const Eval& eval, MaterialPoints& points, const BoundaryConditions& bc,
                      double dt);
  template <class Eval>
  void stress_and_move(const Eval& eval, MaterialPoints& points, const BoundaryConditions& bc,
                       double dt, double move_dt);
  template <class Eval>
  void map_at_midpoints(const Eval& eval, MaterialPoints& points, const BoundaryConditions& bc,
                        double dt);
  template <class Eval>
  void move_with_midpoint_velocity(const Eval& eval, MaterialPoints& points,
                                   const BoundaryConditions& bc, double dt);
  template <class Eval>
  auto midpoint_stencil(const Eval& eval, const MaterialPoints& points, size_t p) const;
  template <class Stencil>
  Vec3 remapped_velocity(const Stencil& s) const;
  void hold_rigid_nodes(const BoundaryConditions& bc, double dt);
  // The axes bc's prescribed-velocity entries hold at node i, as a sum of
  // 1 (x), 2 (y) and 4 (z).
  [[nodiscard]] int held_axes(const BoundaryConditions& bc, size_t i) const;
  // Throws, naming the point, if it is outside this solver's box.
  void evaluate(const MaterialPoints& points, size_t p, ShapeStencil& s) const;
  [[nodiscard]] bool inside(const Vec3& x) const;
  // The stencil of point p (a reference or a value, by evaluator).
  template <class Eval>
  void own_material_fields(const Eval& eval, MaterialPoints& points, double dt);
  // The volume of node i's cell share that lies inside the grid (h³ inside,
  // halved at each outer face of a non-periodic axis).
  [[nodiscard]] double nodal_volume(size_t i) const;
  void take_grid_density(MaterialPoints& points, size_t p, double gas_mass, double free_volume,
                         double dt) const;
  template <class Eval>
  decltype(auto) locate(const Eval& eval, const MaterialPoints& points, size_t p) const;
  // Completes `components` lanes of the node sums from `first`.
  void sum_shared(int first, int components);
  template <class Eval>
  void scatter(const Eval& eval, const MaterialPoints& points, const BoundaryConditions& bc,
               bool force);
  void nodal_velocities(const BoundaryConditions& bc, std::vector<Vec3>& out) const;
  [[nodiscard]] Vec3 node_constraint_impulse(const BoundaryConditions& bc, double& face_push) const;
  void apply_node_constraints(const BoundaryConditions& bc, std::vector<Vec3>& field,
                              bool is_velocity) const;
  // Packs two nodal vector fields into kin_ for the point passes.
  void pack_kinematics(const std::vector<Vec3>& first, const std::vector<Vec3>& second);
  // From kin_ packed as (gradient field, carried field): the velocity
  // gradient L at point p and the carried field interpolated there.
  template <class Stencil>
  void point_kinematics(const MaterialPoints& points, size_t p, const Stencil& s, Mat3& L,
                        Vec3& carried) const;
  // point_kinematics for the kLanes points from p at once, one per SIMD
  // lane, with the linear stencil and plain gradients: L into columns
  // i .. i + kLanes - 1 of b, the carried field into carried[0 ..].
  void point_kinematics_lanes(const ShapeFunctionLinear::Kernel& kernel,
                              const MaterialPoints& points, size_t p, MaterialBlock& b, size_t i,
                              Vec3* carried) const;
  // scatter() with forces for the kLanes points from p (linear stencil, no
  // dual-domain part).
  void scatter_lanes(const ShapeFunctionLinear::Kernel& kernel, const MaterialPoints& points,
                     const BoundaryConditions& bc, bool external, size_t p);
  [[nodiscard]] Vec3 external_force(const MaterialPoints& points, const BoundaryConditions& bc,
                                    size_t p) const;
  // The grid-to-point pass for the kLanes points from p (linear
  // stencil): the velocity update, then under update-stress-last the remap
  // of their momenta into sums_, under update-stress-first the move.
  void grid_to_points_lanes(const ShapeFunctionLinear::Kernel& kernel, MaterialPoints& points,
                            const BoundaryConditions& bc, size_t p, double dt);
  // The stencils of the kLanes points from p, one per lane (locate() for
  // kLanes points).
  [[nodiscard]] LinearStencilLanes<kLanes> locate_lanes(const ShapeFunctionLinear::Kernel& kernel,
                                                        const MaterialPoints& points,
                                                        size_t p) const;
  // Throws, naming the first of the kLanes points from p outside this
  // solver's box, if one is; x holds their coordinates across lanes.
  void check_inside_lanes(const MaterialPoints& points, size_t p, const PointLanes (&x)[3]) const;
  void nodal_gradient(const std::vector<Vec3>& v, std::vector<Mat3>& G) const;
  void build_dual(const MaterialPoints& points);
  void add_dual_force();
  void update_stress_block(MaterialPoints& points, size_t p0, size_t m, MaterialBlock& b,
                           double dt) const;
  void move_point(MaterialPoints& points, size_t p, const Vec3& v, double dt) const;
  [[noreturn]] void point_off_grid(const std::string& noun, int64_t id, const Vec3& x,
                                   const Vec3& v, double dt) const;
  void sum_rigid();
  // SolverOptions::contact: the mass gradient of this solver's points to
  // mass_gradient_; the contact impulses on the nodal force (before the
  // update) and on the remapped momentum (before the stress update).
  template <class Eval>
  void map_mass_gradient(const Eval& eval, const MaterialPoints& points);
  [[nodiscard]] Vec3 contact_normal_at(size_t i) const;  // from this field into the other
  // The impulse on this field at node i, both fields' momenta taken
  // `advance` times their forces on (0: as they are); zero where either
  // leaves the node empty.
  [[nodiscard]] Vec3 contact_impulse_at(size_t i, double advance) const;
  void contact_on_forces(double dt);
  void contact_on_remap();
  // The other field's mass at node i (0 without contact).
  [[nodiscard]] double other_mass(size_t i) const {
    return other_sums_.empty() ? 0.0 : other_sums_[i * sums::kStride + sums::kMass];
  }
  void impose_rigid(const BoundaryConditions& bc, std::vector<Vec3>& v) const;
  void hold_prescribed(const MaterialPoints& points, const BoundaryConditions& bc, size_t p,
                       Vec3& vel) const;
  double alpha(const MaterialPoints& points, size_t p) const;

  GridPatch patch_;
  RegularGrid local_;  // the patch as a grid of its own
  std::unique_ptr<ShapeFunction> shape_;
  std::vector<std::unique_ptr<Material>> materials_;
  SolverOptions opt_;
  bool linear_;
  std::unique_ptr<MaterialBlock> block_;  // the stress update's scratch
  Phase phase_ = Phase::kBegin;
  double mass_floor_ = 0.0;
  // Per node: mass, momentum, force (sums:: lanes), summed across ranks in
  // one exchange.
  std::vector<NodeLanes> sums_;
  // Per node: two vector fields a point pass interpolates together.
  std::vector<NodeLanes> kin_;
  std::vector<Vec3> velocity_, acceleration_, remap_velocity_, node_force_;
  std::vector<Vec3> start_positions_;  // PointMove::kMidpoint: where the move starts
  bool midpoint_pending_ = false;      // mapped at the midpoints, not yet moved
  // SolverOptions::contact (contact_fields): per node.
  std::vector<double> mass_gradient_, other_sums_, other_gradient_;
  // Nodes another program holds this step (hold_nodes_of_others): local
  // index, axis and velocity.
  struct OtherHold {
    size_t node;
    size_t axis;
    double velocity;
  };
  std::vector<OtherHold> others_held_;
  std::vector<Vec3> reaction_;
  Vec3 constraint_impulse_{0.0, 0.0, 0.0};
  double outer_face_push_ = 0.0;
  std::vector<std::vector<double>>
      rigid_;  // per point_velocities entry: its points' share of each node's mass
  std::vector<char> unique_node_;
  std::vector<Vec3> share_momentum_;  // per point_velocities entry (held_share_momentum)
  // DDMP: this rank's operator (rows as integrals M_ji), the nodal volumes
  // V_j summed over ranks, nodal velocity gradients, stress moments and the
  // dual part of the internal force.
  std::unique_ptr<DualDomainOperator> dual_;
  std::vector<double> dual_volume_;
  std::vector<Mat3> G_;
  std::vector<std::array<double, 6>> S_;
  std::vector<Vec3> dual_force_;
};

}  // namespace pbms::grid
