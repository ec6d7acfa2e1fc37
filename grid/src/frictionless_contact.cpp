#include "pbms/grid/frictionless_contact.hpp"

#include <cmath>

namespace pbms::grid {

// IEEE subtraction is antisymmetric and the squares of negated values are
// equal, so the swapped call gives -n exactly.
ContactVec contact_normal(const ContactVec& grad_a, const ContactVec& grad_b) {
  ContactVec d{};
  double norm2 = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    d[c] = grad_b[c] - grad_a[c];
    norm2 += d[c] * d[c];
  }
  if (!(norm2 > 0.0)) return {0.0, 0.0, 0.0};
  const double inv = 1.0 / std::sqrt(norm2);
  for (double& c : d) c *= inv;
  return d;
}

// The approach (va - vb) . n is the same number in the swapped call
// ((vb - va) . (-n), each product equal), and so is the reduced mass.
ContactVec frictionless_contact_impulse(double ma, const ContactVec& pa, double mb,
                                        const ContactVec& pb, const ContactVec& n) {
  double approach = 0.0;
  for (std::size_t c = 0; c < 3; ++c) approach += (pa[c] / ma - pb[c] / mb) * n[c];
  if (!(approach > 0.0)) return {0.0, 0.0, 0.0};
  const double reduced = ma * mb / (ma + mb);
  const double j = reduced * approach;
  return {-j * n[0], -j * n[1], -j * n[2]};
}

}  // namespace pbms::grid
