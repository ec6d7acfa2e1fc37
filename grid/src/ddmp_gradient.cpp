#include "pbms/grid/ddmp_gradient.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pbms/error.hpp"

namespace pbms::grid {

namespace {

using Vec3 = std::array<double, 3>;

// Gauss-Legendre rules mapped to [0, 1]; weights sum to 1.
struct GaussRule {
  std::array<double, 4> t{};
  std::array<double, 4> w{};
};

GaussRule gauss_rule(int n) {
  switch (n) {
    case 1:
      return {{0.5}, {1.0}};
    case 2: {
      const double a = 0.5 / std::sqrt(3.0);
      return {{0.5 - a, 0.5 + a}, {0.5, 0.5}};
    }
    case 3: {
      const double a = 0.5 * std::sqrt(0.6);
      return {{0.5 - a, 0.5, 0.5 + a}, {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0}};
    }
    case 4: {
      const double r = 2.0 * std::sqrt(1.2);
      const double x1 = std::sqrt(3.0 / 7.0 - r / 7.0);
      const double x2 = std::sqrt(3.0 / 7.0 + r / 7.0);
      const double w1 = (18.0 + std::sqrt(30.0)) / 72.0;
      const double w2 = (18.0 - std::sqrt(30.0)) / 72.0;
      return {{0.5 - 0.5 * x2, 0.5 - 0.5 * x1, 0.5 + 0.5 * x1, 0.5 + 0.5 * x2}, {w2, w1, w1, w2}};
    }
    default:
      throw Error("DDMP quadrature needs 1 to 4 Gauss points per axis, got " + std::to_string(n));
  }
}

std::array<int, 3> cell_ijk(const RegularGrid& grid, std::int64_t index) {
  const auto& n = grid.cells();
  const auto i = static_cast<int>(index % n[0]);
  index /= n[0];
  return {i, static_cast<int>(index % n[1]), static_cast<int>(index / n[1])};
}

// Accumulates into the row of node j, which holds at most a few dozen
// entries, so a linear search beats any map.
void add_to_row(std::vector<DualDomainOperator::Entry>& row, std::int64_t i, const Vec3& v) {
  for (auto& e : row) {
    if (e.node == i) {
      for (int d = 0; d < 3; ++d) e.d[d] += v[d];
      return;
    }
  }
  row.push_back({i, v});
}

using Rows = std::vector<std::vector<DualDomainOperator::Entry>>;  // per slot

// Omega: the sorted, distinct cells that hold a position.
std::vector<std::int64_t> cells_holding(const RegularGrid& grid,
                                        std::span<const std::array<double, 3>> positions) {
  std::vector<std::int64_t> cells;
  cells.reserve(positions.size());
  for (const auto& x : positions) {
    const auto c = grid.cell_of(x);
    if (!c) {
      throw Error("material point (" + std::to_string(x[0]) + ", " + std::to_string(x[1]) + ", " +
                  std::to_string(x[2]) + ") is outside the MPM grid");
    }
    cells.push_back(grid.cell_index(*c));
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

// Where the quadrature points of a cell lie and what they weigh.
struct CellQuadrature {
  GaussRule rule;
  int ng = 0;  // Gauss points per axis
  int ns = 0;  // subcells per axis
  double h = 0.0;
  double sub = 0.0;
  double sub_volume = 0.0;
};

// One cell's integrals over the union of its quadrature points' stencil
// nodes, kept from cell to cell so that only a cell with more nodes than any
// before it allocates.
struct CellBlock {
  std::vector<ShapeStencil> at;  // per quadrature point
  std::vector<double> weight;    // per quadrature point
  std::vector<std::int64_t> local_node;
  std::vector<double> local_volume;
  std::vector<Vec3> local_block;  // [j * local_node.size() + i]
  std::vector<int> local_of;      // [point * kMaxNodes + q]
};

void evaluate_stencils(const RegularGrid& grid, const ShapeFunction& shape,
                       const CellQuadrature& quad, std::int64_t cell, CellBlock& cb) {
  const GaussRule& rule = quad.rule;
  const int ng = quad.ng;
  const int ns = quad.ns;
  const double h = quad.h;
  const double sub = quad.sub;
  const auto c = cell_ijk(grid, cell);
  std::size_t g = 0;
  for (int sc = 0; sc < ns; ++sc)
    for (int sb = 0; sb < ns; ++sb)
      for (int sa = 0; sa < ns; ++sa)
        for (int gc = 0; gc < ng; ++gc)
          for (int gb = 0; gb < ng; ++gb)
            for (int ga = 0; ga < ng; ++ga, ++g) {
              const std::array<int, 3> s{sa, sb, sc};
              const std::array<int, 3> k{ga, gb, gc};
              Vec3 x{};
              for (int d = 0; d < 3; ++d) {
                x[d] = grid.origin()[d] + h * c[d] + sub * (s[d] + rule.t[k[d]]);
              }
              cb.weight[g] = quad.sub_volume * rule.w[ga] * rule.w[gb] * rule.w[gc];
              shape.evaluate(grid, x, cb.at[g]);
            }
}

// Numbers the cell's nodes in order of first appearance.
void number_local_nodes(CellBlock& cb) {
  const auto& at = cb.at;
  cb.local_node.clear();
  cb.local_of.assign(at.size() * ShapeStencil::kMaxNodes, 0);
  for (std::size_t p = 0; p < at.size(); ++p) {
    for (int q = 0; q < at[p].count; ++q) {
      const auto it = std::find(cb.local_node.begin(), cb.local_node.end(), at[p].node[q]);
      cb.local_of[p * ShapeStencil::kMaxNodes + q] = static_cast<int>(it - cb.local_node.begin());
      if (it == cb.local_node.end()) cb.local_node.push_back(at[p].node[q]);
    }
  }
}

void integrate_block(CellBlock& cb) {
  const std::size_t m = cb.local_node.size();
  cb.local_volume.assign(m, 0.0);
  cb.local_block.assign(m * m, Vec3{});
  for (std::size_t p = 0; p < cb.at.size(); ++p) {
    const ShapeStencil& st = cb.at[p];
    const int* lq = &cb.local_of[p * ShapeStencil::kMaxNodes];
    for (int qj = 0; qj < st.count; ++qj) {
      const double wn = cb.weight[p] * st.N[qj];
      if (wn == 0.0) continue;
      const auto j = static_cast<std::size_t>(lq[qj]);
      cb.local_volume[j] += wn;
      for (int qi = 0; qi < st.count; ++qi) {
        auto& b = cb.local_block[j * m + static_cast<std::size_t>(lq[qi])];
        for (int d = 0; d < 3; ++d) b[d] += wn * st.dN[qi][d];
      }
    }
  }
}

// Adds the cell's block to the global rows, opening a slot for each node
// the cell is the first to reach.
void scatter_block(const CellBlock& cb, std::vector<std::int32_t>& slot_of_node,
                   std::vector<double>& volume, Rows& rows) {
  const std::size_t m = cb.local_node.size();
  for (std::size_t j = 0; j < m; ++j) {
    if (cb.local_volume[j] == 0.0) continue;
    auto& slot = slot_of_node[static_cast<std::size_t>(cb.local_node[j])];
    if (slot < 0) {
      slot = static_cast<std::int32_t>(rows.size());
      rows.emplace_back();
      volume.push_back(0.0);
    }
    volume[static_cast<std::size_t>(slot)] += cb.local_volume[j];
    for (std::size_t i = 0; i < m; ++i) {
      const Vec3& b = cb.local_block[j * m + i];
      if (b[0] == 0.0 && b[1] == 0.0 && b[2] == 0.0) continue;  // supports do not meet here
      add_to_row(rows[static_cast<std::size_t>(slot)], cb.local_node[i], b);
    }
  }
}

// Sorts each row by node and packs the rows into one array.
void pack_rows(Rows& rows, const std::vector<double>& volume, DualDomainRows rows_kind,
               std::vector<std::size_t>& row_begin,
               std::vector<DualDomainOperator::Entry>& entries) {
  using Entry = DualDomainOperator::Entry;
  row_begin.reserve(rows.size() + 1);
  row_begin.push_back(0);
  for (std::size_t s = 0; s < rows.size(); ++s) {
    auto& row = rows[s];
    std::sort(row.begin(), row.end(),
              [](const Entry& a, const Entry& b) { return a.node < b.node; });
    const double inv_v = rows_kind == DualDomainRows::kAverage ? 1.0 / volume[s] : 1.0;
    for (auto& e : row) {
      for (int d = 0; d < 3; ++d) e.d[d] *= inv_v;
      entries.push_back(e);
    }
    row_begin.push_back(entries.size());
  }
}

}  // namespace

DualDomainOperator::DualDomainOperator(const RegularGrid& grid, const ShapeFunction& shape,
                                       std::span<const std::array<double, 3>> positions,
                                       DualDomainQuadrature quadrature, DualDomainRows rows_kind)
    : node_count_(grid.node_count()) {
  const GaussRule rule = gauss_rule(quadrature.gauss_points);
  const int ng = quadrature.gauss_points;
  const int ns = quadrature.subcells;
  if (ns < 1 || ns > 8) {
    throw Error("DDMP quadrature needs 1 to 8 subcells per axis, got " + std::to_string(ns));
  }

  cells_ = cells_holding(grid, positions);

  slot_of_node_.assign(static_cast<std::size_t>(node_count_), -1);
  Rows rows;  // per slot: integral of N_j grad N_i
  const double h = grid.cell_size();
  const double sub = h / ns;
  const CellQuadrature quad{rule, ng, ns, h, sub, sub * sub * sub};

  // Per cell: evaluate the stencils at all quadrature points, integrate into
  // a dense block over the union of their nodes, then scatter the block into
  // the global rows once, which keeps the row searches out of the point loop.
  const int points_per_cell = ns * ns * ns * ng * ng * ng;
  CellBlock cb;
  cb.at.resize(static_cast<std::size_t>(points_per_cell));
  cb.weight.resize(cb.at.size());
  for (const std::int64_t cell : cells_) {
    evaluate_stencils(grid, shape, quad, cell, cb);
    number_local_nodes(cb);
    integrate_block(cb);
    scatter_block(cb, slot_of_node_, volume_, rows);
  }
  pack_rows(rows, volume_, rows_kind, row_begin_, entries_);
}

double DualDomainOperator::nodal_volume(std::int64_t node) const {
  const std::int32_t s = slot_of_node_[static_cast<std::size_t>(node)];
  return s < 0 ? 0.0 : volume_[static_cast<std::size_t>(s)];
}

std::span<const DualDomainOperator::Entry> DualDomainOperator::row(std::int64_t node) const {
  const std::int32_t s = slot_of_node_[static_cast<std::size_t>(node)];
  if (s < 0) return {};
  const auto u = static_cast<std::size_t>(s);
  return std::span<const Entry>(entries_).subspan(row_begin_[u], row_begin_[u + 1] - row_begin_[u]);
}

GradientStencils ddmp_gradients(const DualDomainOperator& op,
                                std::span<const ShapeStencil> stencils,
                                std::span<const double> alpha) {
  if (!alpha.empty() && alpha.size() != stencils.size()) {
    throw Error("DDMP: " + std::to_string(alpha.size()) + " blend weights for " +
                std::to_string(stencils.size()) + " material points");
  }
  GradientStencils out;
  out.begin.reserve(stencils.size() + 1);
  out.begin.push_back(0);
  // Position of a node in the current point's output, -1 when absent; reset
  // after each point so the whole call stays linear in the output size.
  std::vector<std::int64_t> where(static_cast<std::size_t>(op.node_count()), -1);
  auto add = [&](std::int64_t node, const Vec3& v, double scale) {
    auto& k = where[static_cast<std::size_t>(node)];
    if (k < 0) {
      k = static_cast<std::int64_t>(out.node.size());
      out.node.push_back(node);
      out.dN.push_back({scale * v[0], scale * v[1], scale * v[2]});
    } else {
      auto& g = out.dN[static_cast<std::size_t>(k)];
      for (int d = 0; d < 3; ++d) g[d] += scale * v[d];
    }
  };

  for (std::size_t p = 0; p < stencils.size(); ++p) {
    const ShapeStencil& st = stencils[p];
    const double a = alpha.empty() ? 0.0 : alpha[p];
    if (!(a >= 0.0 && a <= 1.0)) {
      throw Error("DDMP blend weight must lie in [0, 1], got " + std::to_string(a) +
                  " for material point " + std::to_string(p));
    }
    const std::size_t first = out.node.size();
    for (int q = 0; q < st.count; ++q) add(st.node[q], st.dN[q], a);
    if (a < 1.0) {
      for (int q = 0; q < st.count; ++q) {
        const double w = (1.0 - a) * st.N[q];
        if (w == 0.0) continue;
        for (const auto& e : op.row(st.node[q])) add(e.node, e.d, w);
      }
    }
    for (std::size_t k = first; k < out.node.size(); ++k) {
      where[static_cast<std::size_t>(out.node[k])] = -1;
    }
    out.begin.push_back(out.node.size());
    if (p == 0) {
      // Points of one style have stencils of similar reach: size the output
      // from the first one instead of growing it repeatedly.
      out.node.reserve(out.node.size() * stencils.size());
      out.dN.reserve(out.node.capacity());
    }
  }
  return out;
}

double face_vanishing_blend(const RegularGrid& grid, const std::array<double, 3>& x, double peak) {
  const auto c = grid.cell_of(x);
  if (!c) throw Error("point is outside the MPM grid");
  double a = peak;
  for (int d = 0; d < 3; ++d) {
    const double xi =
        std::clamp((x[d] - grid.origin()[d]) * grid.inverse_cell_size() - (*c)[d], 0.0, 1.0);
    a *= 4.0 * xi * (1.0 - xi);
  }
  return a;
}

}  // namespace pbms::grid
