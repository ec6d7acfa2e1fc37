#include "pbms/coupling/gas_lattice.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace pbms::coupling {
namespace {

using geometry::Vec3;

// Body positions binned in cubes of edge `edge`: a point's neighbours within
// `edge` lie in the 27 bins around its own.
class Bins {
 public:
  Bins(const std::vector<Vec3>& x, double edge) : x_(x), edge_(edge) {
    for (std::size_t i = 0; i < x.size(); ++i) bins_[key(bin_of(x[i]))].push_back(i);
  }
  [[nodiscard]] bool any_within(const Vec3& p, double d) const {
    const auto b = bin_of(p);
    for (std::int64_t i = -1; i <= 1; ++i) {
      for (std::int64_t j = -1; j <= 1; ++j) {
        for (std::int64_t k = -1; k <= 1; ++k) {
          const auto it = bins_.find(key({b[0] + i, b[1] + j, b[2] + k}));
          if (it == bins_.end()) continue;
          for (const std::size_t q : it->second) {
            if (distance_squared(p, x_[q]) <= d * d) return true;
          }
        }
      }
    }
    return false;
  }
  // How many positions lie within `d` of p, d no more than the bin edge.
  [[nodiscard]] std::size_t count_within(const Vec3& p, double d) const {
    const auto b = bin_of(p);
    std::size_t n = 0;
    for (std::int64_t i = -1; i <= 1; ++i) {
      for (std::int64_t j = -1; j <= 1; ++j) {
        for (std::int64_t k = -1; k <= 1; ++k) {
          const auto it = bins_.find(key({b[0] + i, b[1] + j, b[2] + k}));
          if (it == bins_.end()) continue;
          for (const std::size_t q : it->second) n += distance_squared(p, x_[q]) <= d * d ? 1 : 0;
        }
      }
    }
    return n;
  }

 private:
  [[nodiscard]] std::array<std::int64_t, 3> bin_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p[0] / edge_)),
            static_cast<std::int64_t>(std::floor(p[1] / edge_)),
            static_cast<std::int64_t>(std::floor(p[2] / edge_))};
  }
  static std::int64_t key(const std::array<std::int64_t, 3>& b) {
    constexpr std::int64_t kSpan = 1 << 20;  // bins per axis the key tells apart
    return ((b[0] + kSpan / 2) * kSpan + (b[1] + kSpan / 2)) * kSpan + (b[2] + kSpan / 2);
  }
  static double distance_squared(const Vec3& a, const Vec3& b) {
    double s = 0.0;
    for (std::size_t c = 0; c < 3; ++c) s += (a[c] - b[c]) * (a[c] - b[c]);
    return s;
  }

  const std::vector<Vec3>& x_;
  double edge_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> bins_;
};

}  // namespace

std::vector<bool> near_body(const std::vector<Vec3>& points, const std::vector<Vec3>& body,
                            double distance) {
  std::vector<bool> near(points.size(), false);
  if (body.empty() || !(distance > 0.0)) return near;
  const Bins bins(body, distance);
  for (std::size_t i = 0; i < points.size(); ++i) near[i] = bins.any_within(points[i], distance);
  return near;
}

std::vector<bool> in_interstices(const std::vector<Vec3>& points, const std::vector<Vec3>& body,
                                 double lattice_constant) {
  std::vector<bool> inside(points.size(), false);
  if (body.empty() || !(lattice_constant > 0.0)) return inside;
  const double reach = kInterstitialReach * lattice_constant;
  const Bins bins(body, reach);
  for (std::size_t i = 0; i < points.size(); ++i) {
    inside[i] = bins.count_within(points[i], reach) >= kInterstitialNeighbours;
  }
  return inside;
}

std::vector<Vec3> gas_sites(const GasParams& gas, const geometry::Box& box,
                            const std::array<bool, 3>& periodic, const std::vector<Vec3>& body,
                            double lattice_constant) {
  // Sites k with lo <= origin + k s <= hi (< hi on a periodic axis), a
  // hair of slack so that sites on the faces are kept.
  std::array<std::int64_t, 3> first{}, last{};
  for (std::size_t a = 0; a < 3; ++a) {
    const double slack = 1e-9 * gas.spacing;
    first[a] =
        static_cast<std::int64_t>(std::ceil((box.lo[a] - gas.origin[a] - slack) / gas.spacing));
    last[a] =
        static_cast<std::int64_t>(std::floor((box.hi[a] - gas.origin[a] + slack) / gas.spacing));
    if (periodic[a] &&
        gas.origin[a] + static_cast<double>(last[a]) * gas.spacing >= box.hi[a] - slack) {
      --last[a];
    }
  }
  std::vector<Vec3> sites;
  for (std::int64_t k = first[2]; k <= last[2]; ++k) {
    for (std::int64_t j = first[1]; j <= last[1]; ++j) {
      for (std::int64_t i = first[0]; i <= last[0]; ++i) {
        sites.push_back({gas.origin[0] + static_cast<double>(i) * gas.spacing,
                         gas.origin[1] + static_cast<double>(j) * gas.spacing,
                         gas.origin[2] + static_cast<double>(k) * gas.spacing});
      }
    }
  }
  const std::vector<bool> taken = near_body(sites, body, gas.clearance);
  const std::vector<bool> inside = in_interstices(sites, body, lattice_constant);
  std::vector<Vec3> free;
  for (std::size_t s = 0; s < sites.size(); ++s) {
    if (!taken[s] && !inside[s]) free.push_back(sites[s]);
  }
  return free;
}

}  // namespace pbms::coupling
