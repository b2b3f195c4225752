#include "core/mapping/grid_compare.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace irgs {
namespace {

// One echo cone straight up +x from the origin: free cells before 1 m, an occupied arc at 1 m.
OccupancyGrid coneGrid(double resolution_m, double range_m = 1.0) {
  OccupancyGrid grid(resolution_m);
  for (int i = 0; i < 3; ++i)
    grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(20.0), range_m, true, SonarInverseModel{});
  return grid;
}

TEST(GridCompare, AGridAgreesWithItselfCompletely) {
  const OccupancyGrid a = coneGrid(0.01);
  const GridComparison c = compareGrids(a, a);
  EXPECT_TRUE(c.identical);
  EXPECT_EQ(c.resolution_m, 0.01);
  EXPECT_GT(c.compared_cells, 1000u);
  EXPECT_EQ(c.same_class_cells, c.compared_cells);
  EXPECT_EQ(c.agreement, 1.0);
  EXPECT_GT(c.reference_occupied, 10u);
  EXPECT_EQ(c.occupied.f1, 1.0);
  EXPECT_EQ(c.occupied_tolerant.f1, 1.0);
  EXPECT_EQ(c.reference_only + c.candidate_only, 0u);
}

TEST(GridCompare, TwoEmptyGridsAgreeAndOneEmptyGridDoesNot) {
  const OccupancyGrid empty(0.01);
  const GridComparison both = compareGrids(empty, empty);
  EXPECT_EQ(both.compared_cells, 0u);
  EXPECT_EQ(both.agreement, 1.0);
  EXPECT_EQ(both.occupied.f1, 1.0);
  const GridComparison one = compareGrids(coneGrid(0.01), empty);
  EXPECT_EQ(one.agreement, 0.0);
  EXPECT_EQ(one.reference_only, one.compared_cells);
  EXPECT_EQ(one.occupied.recall, 0.0);
  EXPECT_EQ(one.occupied.f1, 0.0);
}

TEST(GridCompare, AShiftedArcMissesExactlyButMatchesWithinTheTolerance) {
  const OccupancyGrid a = coneGrid(0.01, 1.0);
  const OccupancyGrid b = coneGrid(0.01, 1.02);  // the arc 2 cells further out
  const GridComparison c = compareGrids(a, b);
  EXPECT_FALSE(c.identical);
  EXPECT_LT(c.agreement, 1.0);
  EXPECT_LT(c.occupied.f1, 0.5);
  GridCompareOptions options;
  options.tolerance_cells = 3;
  EXPECT_GT(compareGrids(a, b, options).occupied_tolerant.f1, 0.95);
  options.tolerance_cells = 0;
  EXPECT_EQ(compareGrids(a, b, options).occupied_tolerant.f1, c.occupied.f1);
}

// The same cone at 1 cm and at 2 cm: compared on the 2 cm cells, nearly all agree.
TEST(GridCompare, DifferentResolutionsMeetOnTheCoarserLattice) {
  OccupancyGrid fine(0.01);
  OccupancyGrid coarse(0.02);
  for (OccupancyGrid* g : {&fine, &coarse})
    g->integrateSonar({0.0, 0.0}, 0.0, degToRad(30.0), 0.5, true, SonarInverseModel{});
  const GridComparison c = compareGrids(fine, coarse);
  EXPECT_EQ(c.resolution_m, 0.02);
  EXPECT_FALSE(c.identical);
  EXPECT_GT(c.agreement, 0.8);
  EXPECT_GT(c.occupied_tolerant.f1, 0.8);
  GridCompareOptions too_fine;
  too_fine.resolution_m = 0.01;
  EXPECT_THROW(compareGrids(fine, coarse, too_fine), std::invalid_argument);
}

TEST(GridCompare, ClassesFollowTheThresholds) {
  OccupancyGrid a(0.01);
  // One no-echo cone of free log-odds -0.2: above the default free threshold (-0.4).
  SonarInverseModel model;
  model.free_log_odds = -0.2;
  a.integrateSonar({0.0, 0.0}, 0.0, degToRad(20.0), 0.3, false, model);
  const OccupancyGrid empty(0.01);
  EXPECT_EQ(compareGrids(a, empty).compared_cells, 0u);  // unknown in both
  GridCompareOptions options;
  options.free_log_odds = -0.1;
  EXPECT_GT(compareGrids(a, empty, options).compared_cells, 100u);
  options.free_log_odds = 1.0;  // above the occupied threshold
  EXPECT_THROW(compareGrids(a, empty, options), std::invalid_argument);
  EXPECT_TRUE(gridCompareOptionsError(options));
}

}  // namespace
}  // namespace irgs
