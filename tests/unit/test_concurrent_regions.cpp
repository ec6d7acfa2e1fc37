#include <gtest/gtest.h>

#include <memory>

#include "pbms/coupling/concurrent_params.hpp"
#include "pbms/geometry/primitive_regions.hpp"

using namespace pbms;
using namespace pbms::coupling;

namespace {

ConcurrentParams shell_and_core(Solver shell, Solver core, bool core_first) {
  ConcurrentParams p;
  ConcurrentRegion outer{
      "shell", shell,
      std::make_shared<geometry::BlockRegion>(geometry::Vec3{0, 0, 0}, geometry::Vec3{60, 60, 60})};
  ConcurrentRegion inner{"core", core,
                         std::make_shared<geometry::SphereRegion>(geometry::Vec3{30, 30, 30}, 15)};
  p.regions = core_first ? std::vector{inner, outer} : std::vector{outer, inner};
  return p;
}

}  // namespace

// A core nested in a shell: inside the core its solver wins, whichever
// region is listed first, and one word swaps the two.
TEST(ConcurrentRegions, TheInnerRegionOfANestWins) {
  const geometry::Vec3 centre{30, 30, 30}, shell{5, 5, 5}, outside{70, 30, 30};
  for (const bool core_first : {false, true}) {
    const auto p = shell_and_core(Solver::kMpm, Solver::kDpd, core_first);
    EXPECT_EQ(p.solver_at(centre), Solver::kDpd);
    EXPECT_EQ(p.solver_at(shell), Solver::kMpm);
    EXPECT_EQ(p.solver_at(outside), Solver::kDpd);  // in no region: a flyer
    const auto swapped = shell_and_core(Solver::kDpd, Solver::kMpm, core_first);
    EXPECT_EQ(swapped.solver_at(centre), Solver::kMpm);
    EXPECT_EQ(swapped.solver_at(shell), Solver::kDpd);
  }
}

// Regions that touch share a face, not a volume: the first listed keeps it,
// as before nesting was allowed.
TEST(ConcurrentRegions, TouchingRegionsKeepTheFirst) {
  ConcurrentParams p;
  p.regions = {{"left", Solver::kDpd,
                std::make_shared<geometry::BlockRegion>(geometry::Vec3{0, 0, 0},
                                                        geometry::Vec3{10, 10, 10})},
               {"right", Solver::kMpm,
                std::make_shared<geometry::BlockRegion>(geometry::Vec3{10, 0, 0},
                                                        geometry::Vec3{20, 10, 10})}};
  EXPECT_EQ(p.solver_at({5, 5, 5}), Solver::kDpd);
  EXPECT_EQ(p.solver_at({15, 5, 5}), Solver::kMpm);
  EXPECT_FALSE(nests_in(p.regions[0].region->bounds(), p.regions[1].region->bounds()));
  EXPECT_FALSE(nests_in(p.regions[0].region->bounds(), p.regions[0].region->bounds()));
}
