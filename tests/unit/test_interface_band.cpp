// The interface band between two regions on one grid.
#include <gtest/gtest.h>

#include "pbms/coupling/interface_band.hpp"
#include "pbms/error.hpp"
#include "pbms/geometry/primitive_regions.hpp"

using namespace pbms;
using namespace pbms::coupling;

// A rod split at x = 40 Å, 4 Å cells: with a 6 Å margin the band is the
// slab 34..46 Å, and its nodes those of the cells that slab touches.
TEST(InterfaceBand, PlanarSplitGivesTheSlabAroundTheInterface) {
  const grid::RegularGrid g({0, 0, 0}, 4.0, {20, 5, 5});
  const geometry::BlockRegion left({0, 0, 0}, {40, 20, 20});
  const geometry::BlockRegion right({40, 0, 0}, {80, 20, 20});
  const InterfaceBand band(g, left, right, 6.0);
  EXPECT_DOUBLE_EQ(band.box().lo[0], 34.0);
  EXPECT_DOUBLE_EQ(band.box().hi[0], 46.0);
  EXPECT_EQ(band.nodes().lo[0], 8);   // the cell [32, 36) holds 34
  EXPECT_EQ(band.nodes().hi[0], 13);  // the cell [44, 48) holds 46: nodes 11 and 12
  EXPECT_EQ(band.nodes().lo[1], 0);
  EXPECT_EQ(band.nodes().hi[1], 6);
  // A particle inside the band deposits only there; one far away nowhere
  // in it; one straddling the band's edge is not covered.
  EXPECT_TRUE(band.covers({40.0, 10.0, 10.0}));
  EXPECT_TRUE(band.covers({10.0, 10.0, 10.0}));
  EXPECT_FALSE(band.covers({30.0, 10.0, 10.0}));
}

TEST(InterfaceBand, RegionsTooFarApartAreRefused) {
  const grid::RegularGrid g({0, 0, 0}, 4.0, {20, 5, 5});
  const geometry::BlockRegion left({0, 0, 0}, {20, 20, 20});
  const geometry::BlockRegion right({60, 0, 0}, {80, 20, 20});
  EXPECT_THROW(InterfaceBand(g, left, right, 6.0), Error);
}
