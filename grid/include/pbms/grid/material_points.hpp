// Material points in structure-of-arrays form: each solver pass streams the
// few arrays it needs. Indices are local to one rank; `id` is global.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

// GCC 12 warns inside its own AVX-512 intrinsics when Eigen uses them
// (GCC bug 105593, fixed in 13); nothing of ours is uninitialised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/LU>  // determinant()
#pragma GCC diagnostic pop

#include "pbms/grid/material_point_state.hpp"
#include "pbms/grid/symmetric_tensor.hpp"

namespace pbms::grid {

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
  // Bit g set: the point belongs to group g of the run (loads, grips and
  // probes name groups; the bits travel with the point between ranks).
  std::vector<uint32_t> groups;
  // Work the stress has done on the point since the start, in energy units:
  // the energy a rate-form (hypoelastic) model has no state function for.
  std::vector<double> work;

  [[nodiscard]] size_t size() const { return x.size(); }
  [[nodiscard]] double volume(size_t p) const { return volume0[p] * F[p].determinant(); }

  // Appends a point at rest, undeformed, with the given initial state.
  void add(int64_t gid, const Vec3& pos, double vol, const MaterialPointState& s, int mat,
           uint32_t group_bits = 0) {
    id.push_back(gid);
    x.push_back(pos);
    v.push_back({0.0, 0.0, 0.0});
    mass.push_back(s.density * vol);
    volume0.push_back(vol);
    F.push_back(Mat3::Identity());
    state.push_back(s);
    material.push_back(mat);
    groups.push_back(group_bits);
    work.push_back(0.0);
  }
  [[nodiscard]] bool in_group(size_t p, uint32_t mask) const { return (groups[p] & mask) != 0; }

  // Moves point p to the end of `to` and removes it here (the last point
  // takes its index).
  void move_to(size_t p, MaterialPoints& to) {
    to.id.push_back(id[p]);
    to.x.push_back(x[p]);
    to.v.push_back(v[p]);
    to.mass.push_back(mass[p]);
    to.volume0.push_back(volume0[p]);
    to.F.push_back(F[p]);
    to.state.push_back(state[p]);
    to.material.push_back(material[p]);
    to.groups.push_back(groups[p]);
    to.work.push_back(work[p]);
    erase(p);
  }
  void erase(size_t p) {
    const size_t last = size() - 1;
    if (p != last) {
      id[p] = id[last];
      x[p] = x[last];
      v[p] = v[last];
      mass[p] = mass[last];
      volume0[p] = volume0[last];
      F[p] = F[last];
      state[p] = state[last];
      material[p] = material[last];
      groups[p] = groups[last];
      work[p] = work[last];
    }
    id.pop_back();
    x.pop_back();
    v.pop_back();
    mass.pop_back();
    volume0.pop_back();
    F.pop_back();
    state.pop_back();
    material.pop_back();
    groups.pop_back();
    work.pop_back();
  }
};

}  // namespace pbms::grid
