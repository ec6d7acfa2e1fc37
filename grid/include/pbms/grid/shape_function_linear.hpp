// Trilinear tent functions: the 8 nodes of the cell that holds the point,
// N_i(x) = prod_d (1 - |x_d - X_i,d| / h). The shape function of the seed's
// MPM (§2.4.2); its gradient jumps on cell faces, which is what DDMP smooths.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "pbms/grid/shape_function.hpp"
#include "pbms/simd/lanes8.hpp"
#include "pbms/simd/point_lanes.hpp"

namespace pbms::grid {

// The stencil of the linear style with its node count fixed at compile
// time, so that a solver's loops over it unroll. Weights and gradient
// components are kept per component across the eight corners (one SIMD
// register each) instead of ShapeStencil's per-node triples; grad() gives
// either layout's gradient of node q.
struct LinearStencil {
  static constexpr int count = 8;
  std::array<std::int64_t, 8> node{};
  Lanes8 N{};
  Lanes8 dNx{}, dNy{}, dNz{};
};

inline std::array<double, 3> grad(const LinearStencil& s, int q) {
  return {s.dNx[q], s.dNy[q], s.dNz[q]};
}
inline const std::array<double, 3>& grad(const ShapeStencil& s, int q) {
  return s.dN[static_cast<std::size_t>(q)];
}

// Makes the compiler keep the stencil's weights in memory from here on: a
// node loop then reads node q's weight with a broadcast load, which AVX-512
// folds into the multiply-add (an embedded broadcast, on the load ports),
// instead of a register permute, which competes with the multiply-adds for
// one port. Worth it where a node takes several weights (MPM's P2G and
// velocity gradient: 7 % of the step); a loop with one weight per node is
// faster without. A no-op for any other stencil.
inline void keep_weights_in_memory(LinearStencil& s) {
  asm("" : "+m"(s));
}
inline void keep_weights_in_memory(const ShapeStencil&) {}

// The stencils of W points at once, point k in lane k, for passes that
// run across points (W = simd::kPointLanes). Per axis d, w[d][0] is the
// lower corner's factor (1 - xi) and w[d][1] the upper's (xi); corner
// q = a + 2b + 4c takes w[0][a] w[1][b] w[2][c], the same products, in the
// same order, as LinearStencil's lane q, so both layouts give identical
// weights.
template <int W>
struct LinearStencilLanes {
  using Real = simd::Lanes<W>;
  // No member initialisers: the kernel writes every field, and zeroing
  // the stencil first (a rep stos per eight points that the compiler did
  // not drop) cost the P2G pass several per cent.
  alignas(64) std::array<std::int64_t, W> base;  // each point's lower corner node
  std::int64_t stride_y, stride_z;               // node index steps along y and z
  Real w[3][2];
  double slope[3][2];  // d w[d][c] / d x_d: -1/h, +1/h

  [[nodiscard]] std::int64_t corner_offset(int q) const {
    return (q & 1) + ((q >> 1) & 1) * stride_y + (q >> 2) * stride_z;
  }
  // Corner q of a cell whose lower corner is `cell`, in an array of nodes.
  template <class T>
  [[nodiscard]] T* corner(T* cell, int q) const {
    return cell + corner_offset(q);
  }
  // The node index of point k's corner q.
  [[nodiscard]] std::int64_t node(std::size_t k, int q) const { return base[k] + corner_offset(q); }
  [[nodiscard]] Real N(int q) const { return w[0][q & 1] * w[1][(q >> 1) & 1] * w[2][q >> 2]; }
  // The gradient of corner q's weight, one vector per axis.
  void dN(int q, Real (&g)[3]) const {
    const int a = q & 1, b = (q >> 1) & 1, c = q >> 2;
    g[0] = slope[0][a] * w[1][b] * w[2][c];
    g[1] = w[0][a] * slope[1][b] * w[2][c];
    g[2] = w[0][a] * w[1][b] * slope[2][c];
  }
};

class ShapeFunctionLinear final : public ShapeFunction {
 public:
  // The evaluation for one grid with the grid's constants taken once: an
  // inline path for solvers that check for this style once per step.
  // evaluate() runs the same arithmetic, so both give identical results.
  class Kernel {
   public:
    explicit Kernel(const RegularGrid& grid)
        : last_cell_(grid.cells()),
          stride_y_(grid.nodes_per_axis()[0]),
          stride_z_(std::int64_t{grid.nodes_per_axis()[0]} * grid.nodes_per_axis()[1]) {
      for (auto& c : last_cell_) c -= 1;
      for (int q = 0; q < 8; ++q) {
        offset_[q] = (q & 1) + ((q >> 1) & 1) * stride_y_ + (q >> 2) * stride_z_;
      }
      for (int d = 0; d < 3; ++d) {
        origin4_[d] = grid.origin()[static_cast<std::size_t>(d)];
        inv_h4_[d] = grid.inverse_cell_size();
        slope_[d] = kSign[d] * inv_h4_[d];
      }
      inv_h4_[3] = 1.0;
    }

    // x must lie in the grid (RegularGrid::contains).
    [[gnu::always_inline]] void operator()(const std::array<double, 3>& x,
                                           LinearStencil& out) const {
      // The cell is RegularGrid::cell_of's (x >= origin, so truncation is
      // floor; the same multiply by 1/h); the clamp keeps round-off in the
      // local coordinate from pushing N out of [0, 1]. Per axis, the lower
      // corner weighs 1 - xi and the upper xi; lane q is corner (q & 1,
      // q >> 1 & 1, q >> 2). No division: its latency, on every point's
      // critical path, cost the MPM step 8 % when the cell came from r / h.
      using Lanes4 = double __attribute__((vector_size(32)));
      const Lanes4 r = Lanes4{x[0], x[1], x[2], 0.0} - origin4_;
      const Lanes4 scaled = r * inv_h4_;
      Lanes8 w[3];
      int cell[3];
      for (int d = 0; d < 3; ++d) {
        cell[d] = std::clamp(static_cast<int>(scaled[d]), 0, last_cell_[d]);
        const double xi = std::clamp(scaled[d] - cell[d], 0.0, 1.0);
        w[d] = kLower[d] + xi * kSign[d];  // 1 + xi * -1 is 1 - xi exactly
      }
      const std::int64_t base = cell[0] + stride_y_ * cell[1] + stride_z_ * cell[2];
      for (int q = 0; q < 8; ++q) out.node[q] = base + offset_[q];
      out.N = w[0] * w[1] * w[2];
      out.dNx = slope_[0] * w[1] * w[2];
      out.dNy = w[0] * slope_[1] * w[2];
      out.dNz = w[0] * w[1] * slope_[2];
    }

    // W points at once, coordinate d of point k in x[d][k]; each lane's
    // arithmetic is the single-point operator's. The cell goes through 32
    // bits, the width every instruction set converts doubles to in
    // registers (x lies in the grid, so it fits).
    template <int W>
    [[gnu::always_inline]] void operator()(const simd::Lanes<W> (&x)[3],
                                           LinearStencilLanes<W>& out) const {
      using Real = simd::Lanes<W>;
      using Cell = simd::Int32Lanes<W>;
      simd::IndexLanes<W> base{};
      const std::int64_t stride[3] = {1, stride_y_, stride_z_};
      for (int d = 0; d < 3; ++d) {
        const Real scaled = (x[d] - origin4_[d]) * inv_h4_[d];
        Cell cell = __builtin_convertvector(scaled, Cell);  // truncation, as static_cast
        cell = cell < 0 ? Cell{} : cell;
        const std::int32_t last = last_cell_[static_cast<std::size_t>(d)];
        cell = cell > last ? Cell{} + last : cell;
        Real xi = scaled - __builtin_convertvector(cell, Real);
        xi = xi < 0.0 ? Real{} : xi;
        xi = xi > 1.0 ? Real{} + 1.0 : xi;
        out.w[d][0] = 1.0 - xi;
        out.w[d][1] = xi;
        out.slope[d][0] = -inv_h4_[d];
        out.slope[d][1] = inv_h4_[d];
        base += __builtin_convertvector(cell, simd::IndexLanes<W>) * stride[d];
      }
      __builtin_memcpy(out.base.data(), &base, sizeof base);
      out.stride_y = stride_y_;
      out.stride_z = stride_z_;
    }

    void operator()(const std::array<double, 3>& x, ShapeStencil& out) const {
      LinearStencil s;
      (*this)(x, s);
      out.count = 8;
      for (int q = 0; q < 8; ++q) {
        const auto qq = static_cast<std::size_t>(q);
        out.node[qq] = s.node[qq];
        out.N[qq] = s.N[q];
        out.dN[qq] = grad(s, q);
      }
    }

   private:
    std::array<int, 3> last_cell_;
    std::int64_t stride_y_, stride_z_;
    std::array<std::int64_t, 8> offset_{};
    Lanes8 slope_[3]{};  // d N / d x_d of each corner's axis-d factor
    // Origin and 1/h per axis; lane 3 is padding.
    double __attribute__((vector_size(32))) origin4_{}, inv_h4_{};

    static constexpr Lanes8 kLower[3] = {
        {1, 0, 1, 0, 1, 0, 1, 0}, {1, 1, 0, 0, 1, 1, 0, 0}, {1, 1, 1, 1, 0, 0, 0, 0}};
    static constexpr Lanes8 kSign[3] = {
        {-1, 1, -1, 1, -1, 1, -1, 1}, {-1, -1, 1, 1, -1, -1, 1, 1}, {-1, -1, -1, -1, 1, 1, 1, 1}};
  };

  // Nodes come in the cell's corner order, x offset fastest: node a + 2b + 4c
  // is the corner (cx + a, cy + b, cz + c).
  void evaluate(const RegularGrid& grid, const std::array<double, 3>& x,
                ShapeStencil& out) const override;
  [[nodiscard]] int support_nodes() const override { return 8; }
  [[nodiscard]] std::string_view name() const override { return "linear"; }
};

}  // namespace pbms::grid
