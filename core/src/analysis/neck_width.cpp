#include "pbms/analysis/neck_width.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "pbms/error.hpp"

namespace pbms::analysis {

NeckSlabs::NeckSlabs(const std::array<double, 4>& first, const std::array<double, 4>& second,
                     double a, int rod_axis)
    : a_(a), slab_(0.5 * a) {
  if (!(first[0] > 0.0) || !(second[0] > 0.0)) throw Error("a neck needs two bodies with members");
  for (std::size_t c = 0; c < 3; ++c) {
    c0_[c] = first[1 + c] / first[0];
    axis_[c] = static_cast<int>(c) == rod_axis ? 0.0 : second[1 + c] / second[0] - c0_[c];
    length_ += axis_[c] * axis_[c];
  }
  length_ = std::sqrt(length_);
  if (!(length_ > 0.0)) throw Error("a neck needs two bodies whose centres differ");
  for (double& u : axis_) u /= length_;
  // Slabs over the middle half of the line, one centred on its midpoint (so
  // that a gap of a plane spacing shows).
  const auto half =
      static_cast<std::size_t>(std::max(0.0, std::floor(0.25 * length_ / slab_ - 0.5)));
  slabs_ = 2 * half + 1;
  from_ = 0.5 * length_ - (static_cast<double>(half) + 0.5) * slab_;
}

std::optional<std::size_t> NeckSlabs::slab_of(const std::array<double, 3>& x) const {
  double s = 0.0, r2 = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    s += (x[c] - c0_[c]) * axis_[c];
    r2 += (x[c] - c0_[c]) * (x[c] - c0_[c]);
  }
  // Beyond half the centre distance from the line a member belongs to a
  // body's far side, not to the contact (a rod's length beside a sphere).
  if (r2 - s * s > 0.25 * length_ * length_) return std::nullopt;
  const double k = std::floor((s - from_) / slab_);
  if (k < 0.0 || k >= static_cast<double>(slabs_)) return std::nullopt;
  return static_cast<std::size_t>(k);
}

double NeckSlabs::width(const std::vector<double>& per_slab) const {
  const double fewest = *std::min_element(per_slab.begin(), per_slab.end());
  const double area = fewest * (a_ * a_ * a_ / 4.0) / slab_;
  return 2.0 * std::sqrt(area / std::numbers::pi);
}

double closest_approach(const std::vector<std::array<double, 3>>& first,
                        const std::vector<std::array<double, 3>>& second, double reach) {
  using Bin = std::array<long, 3>;
  const auto bin_of = [reach](const std::array<double, 3>& p) {
    return Bin{std::lround(std::floor(p[0] / reach)), std::lround(std::floor(p[1] / reach)),
               std::lround(std::floor(p[2] / reach))};
  };
  std::map<Bin, std::vector<std::size_t>> bins;
  for (std::size_t j = 0; j < second.size(); ++j) bins[bin_of(second[j])].push_back(j);
  double closest = reach;
  for (const auto& p : first) {
    const Bin c = bin_of(p);
    for (long dx = -1; dx <= 1; ++dx) {
      for (long dy = -1; dy <= 1; ++dy) {
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = bins.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == bins.end()) continue;
          for (const std::size_t j : it->second) {
            const auto& q = second[j];
            closest = std::min(closest, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
          }
        }
      }
    }
  }
  return closest;
}

Neck neck_between(const std::vector<std::array<double, 3>>& x, const std::vector<int>& body,
                  double a) {
  std::array<std::array<double, 4>, 2> sums{};
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (body[i] != 0 && body[i] != 1) continue;
    auto& s = sums[static_cast<std::size_t>(body[i])];
    s[0] += 1.0;
    for (std::size_t c = 0; c < 3; ++c) s[1 + c] += x[i][c];
  }
  const NeckSlabs slabs(sums[0], sums[1], a);
  std::vector<double> count(slabs.slabs(), 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (body[i] != 0 && body[i] != 1) continue;
    if (const auto k = slabs.slab_of(x[i])) count[*k] += 1.0;
  }
  std::array<std::vector<std::array<double, 3>>, 2> members;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (body[i] == 0 || body[i] == 1) members[static_cast<std::size_t>(body[i])].push_back(x[i]);
  }
  return {slabs.width(count), slabs.centre_distance(),
          closest_approach(members[0], members[1], closest_reach(a))};
}

}  // namespace pbms::analysis
