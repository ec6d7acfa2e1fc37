// Modified shape-function gradients of the dual domain material point method
// (DDMP): D. Z. Zhang, X. Ma, P. T. Giguere, "Material point method enhanced
// by modified gradient of shape function", J. Comput. Phys. 230 (2011)
// 6379-6398; used in the seed dissertation §7.3 (fig. 7.1) and its
// Appendix 2 program.
//
// Why: with tents, grad N_i jumps on every cell face, so the internal force
// -sum_p V_p sigma_p . grad N_i(x_p) jumps each time a point crosses a face
// (cell-crossing noise). DDMP replaces part of the gradient by one that
// depends on the point's position only through N_j(x_p), which is continuous.
//
// What is computed. Let Omega be the union of the grid cells that hold at
// least one material point. For every node j touching Omega,
//
//   V_j    = integral over Omega of N_j dV                (nodal volume)
//   D_ji   = (1 / V_j) integral over Omega of N_j grad N_i dV,
//
// i.e. D_ji is the average of grad N_i over node j's share of the material
// region. For a point p with blend weight alpha_p in [0, 1],
//
//   gradbar N_i(x_p) = alpha_p grad N_i(x_p) + (1 - alpha_p) sum_j N_j(x_p) D_ji.
//
// alpha = 1 is plain MPM, alpha = 0 is pure dual-domain. A solver uses the
// same gradbar for the force, f_i = -sum_p V_p sigma_p . gradbar N_i(x_p), and
// for the velocity gradient, L_p = sum_i v_i (x) gradbar N_i(x_p), so that the
// discrete power balance sum_i v_i . f_i = -sum_p V_p sigma_p : L_p still holds.
// Equivalent nodal form, cheaper in a solver (row() gives D):
//   S_j = sum_p (1 - alpha_p) V_p sigma_p N_j(x_p)   (scattered like mass)
//   f_i -= sum_j S_j . D_ji   (plus the alpha-weighted plain-MPM force).
//
// Properties, for any alpha_p and any point arrangement: sum_i D_ji = 0 and
// sum_i X_i (x) D_ji = I (because sum_i N_i = 1 and sum_i X_i N_i = x on
// Omega), so gradbar N is exactly linearly complete. D depends on the grid
// and Omega only, so while Omega does not change, the dual part of gradbar
// N_i(x_p) is as smooth in x_p as N_j(x_p).
//
// 1-D reduction (tents, cell length h, bar of section A, Omega = cells
// a..b-1): an interior node has V_j = A h and D_j,j-1 = -1/(2h), D_jj = 0,
// D_j,j+1 = +1/(2h); an end node has V = A h / 2 and a one-sided pair,
// D_b,b-1 = -1/h, D_bb = +1/h (mirrored at a). So the dual strain rate is
// the nodal central difference (v_j+1 - v_j-1) / (2h) interpolated linearly
// to the point (one-sided at the ends), and the dual nodal force is
// A (S_i+1 / V_i+1 - S_i-1 / V_i-1) / 2, each S_j / V_j being a nodal average
// stress; at an end node b it is -A (S_b-1 / V_b-1 + S_b / V_b) / 2. The
// seed's Appendix 2 program computes this force: its nodal array of
// (1 - alpha) sigma_p V_p N_jp / le, doubled on the two end nodes (V = le/2
// there), enters the force as half the difference of the two neighbours
// (A = 1 there); its alpha = 1 is plain MPM, and its alternative alphas are
// functions of the local coordinate xi that vanish at both cell ends, such as
// 4 xi (1 - xi) (see face_vanishing_blend).
// Two deliberate differences from that program: its strain rate takes the
// central difference of the node nearest the point instead of interpolating
// (not the transpose of its force operator), and its force loop skips the
// end nodes' own D_bb terms and leaves force on the empty node past the end;
// integrating over Omega treats the ends consistently.
//
// Choices where the sources leave room. V_j is the grid integral over Omega,
// not the point sum sum_p V_p N_jp: that keeps exact linear completeness for
// any arrangement and reproduces the seed's le and le/2. The price: a cell
// counts as full once it holds a point, so near a free surface that cuts
// cells the dual part smears stress over the empty part of those cells;
// raising alpha there limits that. D changes only when Omega does, i.e. when
// a cell empties or fills, which is the one jump DDMP leaves (at surfaces).
// Rebuilding the operator every step is cheap: one quadrature per occupied
// cell, about the cost of a particle-to-grid transfer.
// The integrals use Gauss-Legendre points inside each occupied cell and the
// ShapeFunction itself, so any registered style works. Tents need 2 points per
// axis (the integrand is at most quadratic per axis) and are then exact;
// styles with breakpoints inside a cell need subcells to be exact (quadratic
// B-splines break at cell centres: subcells = 2, gauss_points = 3).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pbms/grid/regular_grid.hpp"
#include "pbms/grid/shape_function.hpp"

namespace pbms::grid {

// How the dual-domain integrals are evaluated inside each occupied cell.
struct DualDomainQuadrature {
  int gauss_points = 2;  // Gauss-Legendre points per axis, 1..4
  int subcells = 1;      // each cell split into subcells^3 equal parts
};

// What row(j) holds. kAverage: D_ji, ready to use. kIntegral: the integral
// of N_j grad N_i over Omega without the 1 / V_j. Integrals add over cells,
// so a rank that builds its operator from its own points (its part of
// Omega) holds a part of each row and of V_j at the nodes it shares; once
// the parts are summed across ranks, a quantity divided by the summed V_j is
// that of the whole grid. This is how a decomposed solver uses DDMP without
// ghost nodes: sum_i v_i (x) D_ji = (sum_i v_i (x) M_ji) / V_j and
// sum_j S_j . D_ji = sum_j (S_j / V_j) . M_ji, each sum over M local.
enum class DualDomainRows { kAverage, kIntegral };

// The nodal operator D_ji and volumes V_j for one material region Omega.
class DualDomainOperator {
 public:
  struct Entry {
    std::int64_t node;          // i
    std::array<double, 3> d{};  // D_ji, 1/length
  };

  // Omega = cells holding at least one of `positions`. Throws pbms::Error if
  // a position is outside the grid or the quadrature is out of range.
  DualDomainOperator(const RegularGrid& grid, const ShapeFunction& shape,
                     std::span<const std::array<double, 3>> positions,
                     DualDomainQuadrature quadrature = {},
                     DualDomainRows rows = DualDomainRows::kAverage);

  [[nodiscard]] std::int64_t node_count() const { return node_count_; }
  // Sorted linear cell indices of Omega.
  [[nodiscard]] const std::vector<std::int64_t>& occupied_cells() const { return cells_; }
  // V_j; 0 for a node that does not touch Omega.
  [[nodiscard]] double nodal_volume(std::int64_t node) const;
  // D_ji (or M_ji, see DualDomainRows) for all i, sorted by i; empty for a
  // node with V_j = 0.
  [[nodiscard]] std::span<const Entry> row(std::int64_t node) const;

 private:
  std::int64_t node_count_ = 0;
  std::vector<std::int64_t> cells_;
  std::vector<std::int32_t> slot_of_node_;  // -1: node does not touch Omega
  std::vector<double> volume_;              // per slot
  std::vector<std::size_t> row_begin_;      // per slot, plus one
  std::vector<Entry> entries_;
};

// Gradients with a node list per particle of any length: the DDMP gradient of
// a point reaches the neighbours of its stencil nodes (64 nodes for tents),
// more than a ShapeStencil holds. Particle p owns entries
// [begin[p], begin[p + 1]).
struct GradientStencils {
  std::vector<std::size_t> begin;
  std::vector<std::int64_t> node;
  std::vector<std::array<double, 3>> dN;

  [[nodiscard]] std::size_t particles() const { return begin.empty() ? 0 : begin.size() - 1; }
};

// gradbar N_i(x_p) for every point, from the points' stencils (any style,
// evaluated on the grid `op` was built on) and blend weights. An empty
// `alpha` means alpha_p = 0 for all points. The stencil's own nodes come
// first, in stencil order. Throws pbms::Error if alpha has the wrong length
// or a value outside [0, 1].
GradientStencils ddmp_gradients(const DualDomainOperator& op,
                                std::span<const ShapeStencil> stencils,
                                std::span<const double> alpha = {});

// peak * prod_d 4 xi_d (1 - xi_d), xi_d the point's local coordinate in its
// cell: the seed's 4 xi (1 - xi) blend made 3-D. It is 0 on every cell face,
// so the plain-gradient part of gradbar N is continuous there too, and peak
// at the cell centre. Throws pbms::Error if x is outside the grid.
double face_vanishing_blend(const RegularGrid& grid, const std::array<double, 3>& x,
                            double peak = 1.0);

}  // namespace pbms::grid
