// The neck between two sintering bodies (seed §6.4): the smallest diameter
// of their cross-section perpendicular to the line through their centres of
// mass, between the centres. The cross-section is counted in slabs one
// plane spacing (a/2) thick along that line; a slab's area is its members'
// volume (a³/4 each: fcc, four to a cubic cell) over its thickness, and its
// diameter that of the circle of the same area. The neck is the narrowest
// slab in the middle half of the line, where the bodies meet (their far
// sides are wider); 0 while a slab there is empty (no contact yet). Only
// members within half the centre distance of the line count: for two
// spheres that is all of them, for a sphere beside a rod the rod's part
// facing the sphere (elsewhere along the rod its surface, offset by its own
// roughness, would fill the gap's slabs before the bodies touch).
//
// The same rule serves DPD mesoparticles (a = a_cg) and atoms (a = the
// crystal's lattice constant), so that an MD pair and a DPD pair are
// measured alike. Split in two passes so that a caller whose particles are
// spread over ranks can sum the centres and then the slab counts across them.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace pbms::analysis {

class NeckSlabs {
 public:
  // `first`, `second`: each body's {Σm, Σm x, Σm y, Σm z}; `a`: the lattice
  // constant. `rod_axis` 0, 1 or 2: the second body is a rod along that
  // axis, and the line runs from the first's centre square onto the rod's
  // axis (a sphere beside a rod, away from the rod's middle).
  NeckSlabs(const std::array<double, 4>& first, const std::array<double, 4>& second, double a,
            int rod_axis = -1);

  [[nodiscard]] std::size_t slabs() const { return slabs_; }
  [[nodiscard]] double centre_distance() const { return length_; }
  // The slab holding a member at `x`, if it lies in the middle half.
  [[nodiscard]] std::optional<std::size_t> slab_of(const std::array<double, 3>& x) const;
  // The neck's diameter from the members counted in each slab.
  [[nodiscard]] double width(const std::vector<double>& per_slab) const;

 private:
  double a_;
  std::array<double, 3> c0_{}, axis_{};
  double length_ = 0.0, slab_ = 0.0, from_ = 0.0;
  std::size_t slabs_ = 0;
};

struct Neck {
  double width = 0.0;            // Å
  double centre_distance = 0.0;  // Å
  double closest = 0.0;          // Å: of a member of each body, at most closest_reach(a)
};

// How far closest_approach looks: two lattice constants.
[[nodiscard]] inline double closest_reach(double a) {
  return 2.0 * a;
}
// Bodies touch when a member of each is within 1.1 nearest-neighbour
// distances (fcc: a/√2) of the other; the bodies start further apart.
[[nodiscard]] inline double touch_distance(double a) {
  return 1.1 * a / 1.4142135623730951;
}

// The smallest distance between a member of `first` and one of `second`,
// or `reach` if none is closer; binned, so linear in the members.
[[nodiscard]] double closest_approach(const std::vector<std::array<double, 3>>& first,
                                      const std::vector<std::array<double, 3>>& second,
                                      double reach);

// Both passes and the closest approach over one set of equal-mass members:
// body[i] 0 or 1 puts member i in the first or second body, any other
// value in neither.
[[nodiscard]] Neck neck_between(const std::vector<std::array<double, 3>>& x,
                                const std::vector<int>& body, double a);

}  // namespace pbms::analysis
