#include "pbms/geometry/lattice_fill.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::geometry {

namespace {

// Enough for any real system filled by one call, and small enough to turn a
// lattice constant in the wrong units into an error instead of a hang.
constexpr double kMaxCandidateSites = 1e10;

using HalfCell = std::array<int, 3>;

// Basis sites in units of half the lattice constant: in those units every
// site of every cubic lattice has integer coordinates, which is what makes
// plane indices exact.
std::span<const HalfCell> basis(LatticeStyle style) {
  static constexpr std::array<HalfCell, 1> kSc{{{0, 0, 0}}};
  static constexpr std::array<HalfCell, 2> kBcc{{{0, 0, 0}, {1, 1, 1}}};
  static constexpr std::array<HalfCell, 4> kFcc{{{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}}};
  switch (style) {
    case LatticeStyle::kSc:
      return kSc;
    case LatticeStyle::kBcc:
      return kBcc;
    case LatticeStyle::kFcc:
      return kFcc;
  }
  throw Error("unknown lattice style");
}

constexpr std::array<LatticeStyle, 3> kStyles{LatticeStyle::kSc, LatticeStyle::kBcc,
                                              LatticeStyle::kFcc};

struct Site {
  // Plane indices along z, y, x: site x coordinate d is origin[d] +
  // plane * spacing[d], so comparing these integers sorts by z, y, x exactly.
  std::array<std::int64_t, 3> zyx_plane;
  Vec3 x;
};

bool all_finite(const Vec3& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

void check_lattice_inputs(double a, const Vec3& origin) {
  if (!(a > 0.0) || !std::isfinite(a)) {
    throw Error(fmt::format("lattice constant must be a positive number, got {}", a));
  }
  if (!all_finite(origin)) {
    throw Error(fmt::format("lattice origin must be finite, got ({}, {}, {})", origin[0], origin[1],
                            origin[2]));
  }
}

// Cells [lo, hi) per crystal axis, in units of the lattice constant.
struct CellRange {
  std::array<std::int64_t, 3> lo{};
  std::array<std::int64_t, 3> hi{};
};

// The cells whose sites can land in the box: the box corners in crystal
// coordinates (units of a), widened by a cell against rounding.
CellRange candidate_cells(const Box& b, double a, const Orientation& orient, const Vec3& origin,
                          std::size_t basis_size) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 q_lo{kInf, kInf, kInf};
  Vec3 q_hi{-kInf, -kInf, -kInf};
  for (int corner = 0; corner < 8; ++corner) {
    Vec3 p{};
    for (int d = 0; d < 3; ++d) p[d] = ((corner >> d) & 1 ? b.hi[d] : b.lo[d]) - origin[d];
    const Vec3 q = orient.to_crystal(p);
    for (int d = 0; d < 3; ++d) {
      q_lo[d] = std::min(q_lo[d], q[d] / a);
      q_hi[d] = std::max(q_hi[d], q[d] / a);
    }
  }
  CellRange range;
  double candidates = static_cast<double>(basis_size);
  for (int d = 0; d < 3; ++d) {
    const double lo = std::floor(q_lo[d]) - 1.0;
    const double hi = std::ceil(q_hi[d]) + 1.0;
    candidates *= hi - lo;
    // Checked before the casts below, which would overflow for absurd sizes.
    if (!(candidates <= kMaxCandidateSites) || !(std::abs(lo) < 1e15) || !(std::abs(hi) < 1e15)) {
      throw Error(fmt::format(
          "filling a region spanning {} x {} x {} with lattice constant {} would test more than "
          "{:g} sites; check the lattice constant's units, or fill each rank's part separately",
          b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2], a, kMaxCandidateSites));
    }
    range.lo[d] = static_cast<std::int64_t>(lo);
    range.hi[d] = static_cast<std::int64_t>(hi);
  }
  return range;
}

// Box coordinate d of a site with half-cell coordinates c is
// a (unit_d . c) / 2 = (axis_d . c) * a / (2 |axis_d|): an integer plane
// index times a fixed spacing. For the identity orientation the spacing is
// a / 2 exactly, so a site n cells from the origin sits at origin + n a
// bit for bit, the same number a caller writes for a block face.
struct PlaneGrid {
  std::array<std::array<std::int64_t, 3>, 3> axis{};
  Vec3 spacing{};
};

PlaneGrid plane_grid(const Orientation& orient, double a) {
  PlaneGrid planes;
  for (int d = 0; d < 3; ++d) {
    for (int c = 0; c < 3; ++c) planes.axis[d][c] = orient.axis(d)[c];
    planes.spacing[d] = a / (2.0 * orient.axis_length(d));
  }
  return planes;
}

std::vector<Site> sites_inside(const Region& region, const CellRange& cells,
                               std::span<const HalfCell> cell_basis, const PlaneGrid& planes,
                               const Vec3& origin) {
  const auto& axis = planes.axis;
  const auto& spacing = planes.spacing;
  std::vector<Site> sites;
  for (std::int64_t k = cells.lo[2]; k < cells.hi[2]; ++k) {
    for (std::int64_t j = cells.lo[1]; j < cells.hi[1]; ++j) {
      for (std::int64_t i = cells.lo[0]; i < cells.hi[0]; ++i) {
        for (const auto& off : cell_basis) {
          const std::array<std::int64_t, 3> half{2 * i + off[0], 2 * j + off[1], 2 * k + off[2]};
          Site s{};
          for (int d = 0; d < 3; ++d) {
            const std::int64_t plane =
                axis[d][0] * half[0] + axis[d][1] * half[1] + axis[d][2] * half[2];
            s.zyx_plane[2 - d] = plane;
            s.x[d] = origin[d] + static_cast<double>(plane) * spacing[d];
          }
          if (region.contains(s.x)) sites.push_back(s);
        }
      }
    }
  }
  return sites;
}

}  // namespace

LatticeStyle lattice_style_from_name(std::string_view name) {
  for (const auto s : kStyles) {
    if (lattice_style_name(s) == name) return s;
  }
  throw Error(fmt::format("unknown lattice style '{}'; available: sc, bcc, fcc", name));
}

std::string_view lattice_style_name(LatticeStyle style) {
  switch (style) {
    case LatticeStyle::kSc:
      return "sc";
    case LatticeStyle::kBcc:
      return "bcc";
    case LatticeStyle::kFcc:
      return "fcc";
  }
  return "?";
}

int sites_per_cell(LatticeStyle style) {
  return static_cast<int>(basis(style).size());
}

std::vector<Vec3> fill_lattice(LatticeStyle style, const Region& region, double lattice_constant,
                               const Orientation& orient, const Vec3& origin) {
  const double a = lattice_constant;
  check_lattice_inputs(a, origin);
  const Box b = region.bounds();
  if (b.empty()) return {};
  if (!all_finite(b.lo) || !all_finite(b.hi)) {
    throw Error("a lattice can only fill a region with finite bounds");
  }

  const auto cell_basis = basis(style);
  const CellRange cells = candidate_cells(b, a, orient, origin, cell_basis.size());
  std::vector<Site> sites = sites_inside(region, cells, cell_basis, plane_grid(orient, a), origin);

  std::sort(sites.begin(), sites.end(),
            [](const Site& l, const Site& r) { return l.zyx_plane < r.zyx_plane; });
  std::vector<Vec3> positions;
  positions.reserve(sites.size());
  for (const auto& s : sites) positions.push_back(s.x);
  return positions;
}

}  // namespace pbms::geometry
