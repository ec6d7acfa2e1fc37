// Material points in structure-of-arrays form: each solver pass streams the
// few arrays it needs. Indices are local to one rank; `id` is global.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/LU>  // determinant()

#include "materials/material_point_state.hpp"
#include "materials/symmetric_tensor.hpp"

namespace pbms::mpm {

using Vec3 = std::array<double, 3>;

struct MaterialPoints {
  std::vector<int64_t> id;
  std::vector<Vec3> x;          // position, Å
  std::vector<Vec3> v;          // velocity, Å/ps
  std::vector<double> mass;     // g/mol
  std::vector<double> volume0;  // initial volume, Å^3
  std::vector<Mat3> F;          // deformation gradient
  std::vector<MaterialPointState> state;
  std::vector<int> material;  // index into the solver's material list

  [[nodiscard]] size_t size() const { return x.size(); }
  [[nodiscard]] double volume(size_t p) const { return volume0[p] * F[p].determinant(); }

  // Appends a point at rest, undeformed, with the given initial state.
  void add(int64_t gid, const Vec3& pos, double vol, const MaterialPointState& s, int mat) {
    id.push_back(gid);
    x.push_back(pos);
    v.push_back({0.0, 0.0, 0.0});
    mass.push_back(s.density * vol);
    volume0.push_back(vol);
    F.push_back(Mat3::Identity());
    state.push_back(s);
    material.push_back(mat);
  }
};

}  // namespace pbms::mpm
