#include "core/planning/coverage.hpp"

#include <gtest/gtest.h>

#include "core/planning/free_space.hpp"

namespace irgs {
namespace {

// The 250 cm arena of the thesis' real run at 1 cm, with a box inside, inflated by a 10 cm
// robot radius; lanes 20 cm apart.
PlanningGrid arena() {
  PlanningGrid g = PlanningGrid::freeGrid(250, 250, 0.01);
  for (int r = 0; r < 250; ++r)
    for (int c = 0; c < 250; ++c)
      if (r == 0 || c == 0 || r == 249 || c == 249 || (c >= 150 && c < 190 && r >= 90 && r < 130))
        g.setBlocked({c, r}, true);
  return inflate(g, 0.10);
}

class CoveragePatterns : public ::testing::TestWithParam<CoveragePattern> {};

TEST_P(CoveragePatterns, CoversAlmostAllReachableFreeSpaceWithAFreePath) {
  const PlanningGrid g = arena();
  CoverageOptions o;
  o.pattern = GetParam();
  o.lane_cells = 20;
  const CoveragePlan p = planCoverage(g, {12, 12}, o);
  ASSERT_TRUE(p.ok);
  EXPECT_TRUE(polylineIsFree(g, p.points));
  EXPECT_GT(p.reachable_cells, 200u * 200u / 2);
  EXPECT_GE(p.coverage, 0.9);
  EXPECT_LE(p.coverage, 1.0);
  EXPECT_GT(p.length_m, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Patterns, CoveragePatterns,
                         ::testing::Values(CoveragePattern::kSpiral,
                                           CoveragePattern::kBoustrophedon),
                         [](const auto& param_info) {
                           return param_info.param == CoveragePattern::kSpiral
                                      ? std::string("Spiral")
                                      : std::string("Boustrophedon");
                         });

TEST(Coverage, SpiralRunsAlongTheOutlineFirst) {
  const PlanningGrid g = PlanningGrid::freeGrid(100, 100, 0.01);
  const CoveragePlan p = planCoverage(g, {5, 5}, {CoveragePattern::kSpiral, 10});
  ASSERT_GE(p.points.size(), 5u);
  // From the corner: along the bottom edge, then up the right edge (the outer ring first).
  EXPECT_NEAR(p.points[1].y(), p.points[0].y(), 1e-9);
  EXPECT_GT(p.points[1].x(), 0.9);
  EXPECT_NEAR(p.points[2].x(), p.points[1].x(), 1e-9);
  EXPECT_GT(p.points[2].y(), 0.9);
  EXPECT_EQ(p.jumps, 0u);
  EXPECT_GT(p.coverage, 0.99);  // a few corner cells lie just beyond half a lane
}

TEST(Coverage, BlockedStartIsNotOkAndBadLanesThrow) {
  PlanningGrid g = PlanningGrid::freeGrid(10, 10, 0.1);
  g.setBlocked({1, 1}, true);
  EXPECT_FALSE(planCoverage(g, {1, 1}).ok);
  EXPECT_FALSE(planCoverage(g, {-1, 1}).ok);
  EXPECT_THROW(planCoverage(g, {2, 2}, {CoveragePattern::kSpiral, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
