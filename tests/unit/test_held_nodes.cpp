// Rigid groups across programs: after the link adds both sides' held-node
// records, each side keeps only what the other holds, on the axes it
// leaves free itself, with the other's velocity exactly.
#include <gtest/gtest.h>

#include <vector>

#include "pbms/coupling/coupling_side.hpp"
#include "pbms/coupling/held_nodes.hpp"
#include "pbms/error.hpp"

namespace pbms::coupling {
namespace {

// Three nodes: held by neither side; by the other side on all axes; by
// both, this side on x (a grip) and the other on x and z (a flyer).
TEST(HeldNodes, EachSideKeepsWhatTheOtherHoldsOnTheAxesItLeavesFree) {
  const std::vector<double> own = {0, 0,   0, 0,  //
                                   0, 0,   0, 0,  //
                                   1, 0.5, 0, 0};
  const std::vector<double> other = {0, 0,   0,    0,  //
                                     7, 0.1, -0.2, 0.3, 5, 4.75, 0, -1.25};
  std::vector<double> summed(own.size());
  for (std::size_t k = 0; k < own.size(); ++k) summed[k] = own[k] + other[k];
  keep_other_sides_holds(summed, own);
  const std::vector<double> expected = {0, 0,   0,    0,  //
                                        7, 0.1, -0.2, 0.3, 4, 0, 0, -1.25};
  EXPECT_EQ(summed, expected);
}

TEST(HeldNodes, RecordsOfDifferentSizesAreRefused) {
  std::vector<double> summed(2 * kHeldLanes, 0.0);
  const std::vector<double> own(kHeldLanes, 0.0);
  EXPECT_THROW(keep_other_sides_holds(summed, own), Error);
}

}  // namespace
}  // namespace pbms::coupling
