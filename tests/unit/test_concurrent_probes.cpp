// The interface opening from two programs' shares of its two lattice
// planes: the sum of shares must give the planes' own centres whichever
// side holds which particles, and a separation must read positive on
// either side of the MPM region.
#include <gtest/gtest.h>

#include <cmath>

#include "pbms/coupling/concurrent_probes.hpp"

namespace pbms::coupling {
namespace {

using Moments = ConcurrentProbes::PlaneMoments;

// A plane's share: `mass` at start `x0`, moved by `d`.
Moments dpd_share(double mass, double x0, double d) {
  return {mass, mass * d, mass * x0, 0, 0, 0};
}
Moments mpm_share(double mass, double x0, double d) {
  return {0, 0, 0, mass, mass * d, mass * x0};
}
Moments operator+(const Moments& a, const Moments& b) {
  Moments s{};
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = a[k] + b[k];
  return s;
}

TEST(InterfaceOpening, PlanesMovingApartReadPositiveOnEitherSide) {
  // The MPM plane beyond the DPD plane (impact: MPM far half), then before
  // it (tension: MPM left end); each pulled 0.3 Å away from the other.
  EXPECT_NEAR(ConcurrentProbes::opening(dpd_share(2, 103, -0.1), mpm_share(2, 107, 0.2)), 0.3,
              1e-14);
  EXPECT_NEAR(ConcurrentProbes::opening(dpd_share(2, 72, 0.1), mpm_share(2, 68, -0.2)), 0.3, 1e-14);
  // Nearer by 0.25 Å reads negative.
  EXPECT_NEAR(ConcurrentProbes::opening(dpd_share(2, 72, -0.05), mpm_share(2, 68, 0.2)), -0.25,
              1e-14);
}

TEST(InterfaceOpening, SharesFromBothProgramsAddUpToThePlanes) {
  // A body all DPD: both planes on one side, nothing from the other.
  const Moments all_dpd = dpd_share(3, 103, 0.1) + mpm_share(1, 107, 0.5);
  EXPECT_NEAR(ConcurrentProbes::opening(all_dpd, Moments{}), 0.4, 1e-14);
  EXPECT_NEAR(ConcurrentProbes::opening(Moments{}, all_dpd), 0.4, 1e-14);
  // One plane split over both programs: mass-weighted, 1 × 0.0 + 3 × 0.4.
  const Moments a = dpd_share(1, 103, 0.0) + mpm_share(1, 107, 0.5);
  const Moments b = dpd_share(3, 103, 0.4);
  EXPECT_NEAR(ConcurrentProbes::opening(a, b), 0.5 - 0.3, 1e-14);
}

TEST(InterfaceOpening, IsNotANumberWhileAPlaneIsEmpty) {
  EXPECT_TRUE(std::isnan(ConcurrentProbes::opening(dpd_share(2, 103, 0), Moments{})));
  EXPECT_TRUE(std::isnan(ConcurrentProbes::opening(Moments{}, mpm_share(2, 107, 0))));
}

}  // namespace
}  // namespace pbms::coupling
