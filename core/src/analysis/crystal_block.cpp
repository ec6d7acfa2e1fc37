#include "pbms/analysis/crystal_block.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::analysis {
namespace {

using Mat = Eigen::Matrix3d;
using Vec = Eigen::Vector3d;

Mat to_mat(const std::array<double, 9>& a) {
  Mat m;
  for (std::size_t k = 0; k < 9; ++k)
    m(static_cast<Eigen::Index>(k / 3), static_cast<Eigen::Index>(k % 3)) = a[k];
  return m;
}

std::array<double, 9> to_array(const Mat& m) {
  std::array<double, 9> a{};
  for (std::size_t k = 0; k < 9; ++k)
    a[k] = m(static_cast<Eigen::Index>(k / 3), static_cast<Eigen::Index>(k % 3));
  return a;
}

// Each member's site in the frame R (body → box), the lattice's phase taken
// from the members themselves so that the sites need not start on the
// box's origin.
std::vector<std::array<int, 3>> sites_in_frame(const std::vector<Vec>& y,
                                               const std::vector<std::size_t>& members,
                                               const Mat& R, double h) {
  const double k = 2.0 * std::numbers::pi / h;
  Vec s = Vec::Zero(), c = Vec::Zero();
  for (std::size_t p : members) {
    const Vec z = R.transpose() * y[p];
    for (int a = 0; a < 3; ++a) {
      s[a] += std::sin(k * z[a]);
      c[a] += std::cos(k * z[a]);
    }
  }
  Vec phase;
  for (int a = 0; a < 3; ++a) phase[a] = std::atan2(s[a], c[a]) / k;
  std::vector<std::array<int, 3>> index(y.size());
  for (std::size_t p : members) {
    const Vec z = R.transpose() * y[p];
    for (int a = 0; a < 3; ++a) {
      index[p][static_cast<std::size_t>(a)] = static_cast<int>(std::lround((z[a] - phase[a]) / h));
    }
  }
  return index;
}

Mat rotation_onto(const std::vector<Vec>& y, const std::vector<std::size_t>& members,
                  const std::vector<std::array<int, 3>>& index, double h) {
  Vec mean = Vec::Zero();
  for (std::size_t p : members) {
    mean += h * Vec(index[p][0], index[p][1], index[p][2]);
  }
  mean /= static_cast<double>(members.size());
  Mat H = Mat::Zero();
  for (std::size_t p : members) {
    H += (h * Vec(index[p][0], index[p][1], index[p][2]) - mean) * y[p].transpose();
  }
  return to_mat(best_rotation(to_array(H)));
}

// Per axis, the outermost planes holding at least half the median count.
std::array<std::array<int, 2>, 3> whole_face_planes(const std::vector<std::array<int, 3>>& index) {
  std::array<std::array<int, 2>, 3> faces{};
  for (std::size_t a = 0; a < 3; ++a) {
    std::map<int, int> count;
    for (const auto& i : index) ++count[i[a]];
    std::vector<int> sizes;
    sizes.reserve(count.size());
    for (const auto& [plane, n] : count) sizes.push_back(n);
    std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2),
                     sizes.end());
    const double half_median = 0.5 * sizes[sizes.size() / 2];
    std::vector<int> whole;
    for (const auto& [plane, n] : count) {
      if (n >= half_median) whole.push_back(plane);
    }
    if (whole.size() < 2) {
      throw Error(
          fmt::format("crystal block: fewer than two whole lattice planes along {}", "xyz"[a]));
    }
    faces[a] = {whole.front(), whole.back()};
  }
  return faces;
}

}  // namespace

BlockPoint BlockSites::offset(std::size_t particle) const {
  const auto& i = index[particle];
  return {spacing * i[0] - centre[0], spacing * i[1] - centre[1], spacing * i[2] - centre[2]};
}

std::array<double, 9> best_rotation(const std::array<double, 9>& covariance) {
  const Eigen::JacobiSVD<Mat> svd(to_mat(covariance), Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Mat& U = svd.matrixU();
  const Mat& V = svd.matrixV();
  Mat D = Mat::Identity();
  D(2, 2) = (V * U.transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return to_array(V * D * U.transpose());
}

BlockSites fit_block_sites(const std::vector<BlockPoint>& x, double plane_spacing) {
  if (x.size() < 8) throw Error("crystal block: fewer than 8 particles");
  const double h = plane_spacing;
  Vec c = Vec::Zero();
  for (const auto& p : x) c += Vec(p[0], p[1], p[2]);
  c /= static_cast<double>(x.size());
  std::vector<Vec> y;
  double reach = 0.0;
  for (const auto& p : x) {
    y.push_back(Vec(p[0], p[1], p[2]) - c);
    reach = std::max(reach, y.back().norm());
  }
  // Outwards from the centre: within a radius r a turn θ moves a site by at
  // most r θ, so the sites near the centre are assigned right even before
  // the turn is known, and each ring's fit carries the next.
  Mat R = Mat::Identity();
  std::vector<std::size_t> members;
  for (double r = 3.0 * h;; r *= 1.5) {
    members.clear();
    for (std::size_t p = 0; p < y.size(); ++p) {
      if (y[p].norm() <= r) members.push_back(p);
    }
    for (int pass = 0; pass < 3; ++pass) {
      R = rotation_onto(y, members, sites_in_frame(y, members, R, h), h);
    }
    if (r >= reach) break;
  }
  BlockSites sites;
  sites.spacing = h;
  sites.index = sites_in_frame(y, members, R, h);
  for (const auto& i : sites.index) {
    for (std::size_t a = 0; a < 3; ++a) sites.centre[a] += h * i[a];
  }
  for (double& m : sites.centre) m /= static_cast<double>(x.size());
  sites.faces = whole_face_planes(sites.index);
  return sites;
}

void BlockSums::add(const BlockSites& sites, std::size_t particle, const BlockPoint& x) {
  const BlockPoint s = sites.offset(particle);
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) sums[3 * i + j] += s[i] * x[j];
  }
  const auto& index = sites.index[particle];
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t side = 0; side < 2; ++side) {
      if (index[a] != sites.faces[a][side]) continue;
      double* f = &sums[9 + 4 * (2 * a + side)];
      for (std::size_t j = 0; j < 3; ++j) f[j] += x[j];
      f[3] += 1.0;
    }
  }
}

BlockEdges block_edges(const BlockSites& sites, const BlockSums& total) {
  std::array<double, 9> H{};
  std::copy_n(total.sums.begin(), 9, H.begin());
  const Mat R = to_mat(best_rotation(H));
  BlockEdges e;
  e.volume = 1.0;
  for (std::size_t a = 0; a < 3; ++a) {
    const double* lo = &total.sums[9 + 4 * (2 * a)];
    const double* hi = &total.sums[9 + 4 * (2 * a + 1)];
    if (!(lo[3] > 0.0) || !(hi[3] > 0.0)) {
      throw Error(fmt::format("crystal block: a face plane along {} has no particle", "xyz"[a]));
    }
    const Vec d = Vec(hi[0], hi[1], hi[2]) / hi[3] - Vec(lo[0], lo[1], lo[2]) / lo[3];
    const double n = sites.faces[a][1] - sites.faces[a][0];
    e.edge[a] = R.col(static_cast<Eigen::Index>(a)).dot(d) * (n + 1.0) / n;
    e.volume *= e.edge[a];
  }
  const double cosine = std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0);
  e.rotation_deg = std::acos(cosine) * 180.0 / std::numbers::pi;
  return e;
}

}  // namespace pbms::analysis
