// The GUI's planning work without a window: grids, goal preview, region crop, coverage sweep.

#include "app/gui/planning_tasks.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace irgs::gui {
namespace {

// A 4 m x 3 m room with a wall from (2, 0) to (2, 2): the way round is over its top.
WorldMap roomWithWall() {
  WorldMap map;
  map.name = "room";
  Wall outer;
  outer.id = "outer";
  outer.points = {Vec2(0, 0), Vec2(4, 0), Vec2(4, 3), Vec2(0, 3)};
  outer.closed = true;
  Wall middle;
  middle.id = "middle";
  middle.points = {Vec2(2, 0), Vec2(2, 2)};
  map.walls = {outer, middle};
  map.start = Pose2{1.0, 0.5, 0.0};
  return map;
}

TEST(PlanningTasks, GoalPreviewAmendsTheAStarPathAroundAWall) {
  const PlanningSettings settings;
  const PlanningGrids grids = gridsFromWorld(roomWithWall(), 0.16, settings);
  const GoalPreview p = previewGoal(grids, Pose2{1.0, 0.5, 0.0}, Vec2(3.0, 0.5), settings, {});
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.status, PlanStatus::kFound);
  EXPECT_TRUE(p.amended.front().isApprox(Vec2(1.0, 0.5)));
  EXPECT_TRUE(p.amended.back().isApprox(Vec2(3.0, 0.5)));
  EXPECT_LE(p.amended_turns, p.raw_turns);
  EXPECT_LT(p.amended_time_s, p.raw_time_s + 1e-9);
  EXPECT_GT(p.amended_length_m, 3.0);  // it had to go round the wall
  EXPECT_EQ(p.travel.segments.size(), p.amended.size() - 1);
}

TEST(PlanningTasks, GoalPreviewExplainsWhyItCannotPlan) {
  const PlanningSettings settings;
  const PlanningGrids grids = gridsFromWorld(roomWithWall(), 0.16, settings);
  const Pose2 robot{1.0, 0.5, 0.0};
  EXPECT_NE(previewGoal(grids, robot, Vec2(9.0, 9.0), settings, {}).error.find("outside"),
            std::string::npos);
  EXPECT_NE(previewGoal(grids, robot, Vec2(2.0, 1.0), settings, {}).error.find("obstacle"),
            std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(previewGoal(grids, robot, Vec2(nan, 1.0), settings, {}).ok);
  const GoalPreview cancelled = previewGoal(
      grids, robot, Vec2(3.0, 0.5), settings, [] { return 0.0; }, [] { return true; });
  EXPECT_FALSE(cancelled.ok);
  EXPECT_EQ(cancelled.status, PlanStatus::kCancelled);
  EXPECT_FALSE(previewGoal(PlanningGrids{}, robot, Vec2(3.0, 0.5), settings, {}).ok);
}

TEST(PlanningTasks, CropKeepsCellAlignmentAndContent) {
  PlanningGrid grid = PlanningGrid::freeGrid(10, 8, 0.1, Vec2(-0.5, 0.0));
  grid.setBlocked({4, 3}, true);
  Box2 box;
  box.extend(Vec2(-0.2, 0.1));
  box.extend(Vec2(0.3, 0.6));
  const PlanningGrid crop = cropGrid(grid, box);
  // Cell centres inside: cols 3..7 (x = -0.15 .. 0.25), rows 1..5 (y = 0.15 .. 0.55).
  EXPECT_EQ(crop.width, 5);
  EXPECT_EQ(crop.height, 5);
  EXPECT_TRUE(crop.origin.isApprox(Vec2(-0.2, 0.1)));
  EXPECT_FALSE(crop.isFree({1, 2}));
  EXPECT_EQ(crop.blockedCount(), 1u);
  Box2 outside;
  outside.extend(Vec2(5, 5));
  outside.extend(Vec2(6, 6));
  EXPECT_TRUE(cropGrid(grid, outside).empty());
}

TEST(PlanningTasks, CoverageSweepCountsOnlyCellsTheBodyCanReach) {
  // 20 x 20 cells of 5 cm; a blocked column splits off the right-hand 5 columns.
  PlanningGrid raw = PlanningGrid::freeGrid(20, 20, 0.05);
  for (int r = 0; r < 20; ++r)
    raw.setBlocked({14, r}, true);
  const PlanningGrid inflated = inflate(raw, 0.1);
  CoverageSweep sweep(raw, inflated, {5, 10}, 0.1);
  ASSERT_FALSE(sweep.empty());
  // The far side (cols 15..19) is beyond the body's reach from the left part.
  EXPECT_LT(sweep.sweepableCells(), 14u * 20u + 1u);
  EXPECT_DOUBLE_EQ(sweep.coverage(), 0.0);
  sweep.addPosition(Vec2(0.275, 0.525));
  const double one = sweep.coverage();
  EXPECT_GT(one, 0.0);
  sweep.addPosition(Vec2(0.275, 0.525));  // the same place again adds nothing
  EXPECT_DOUBLE_EQ(sweep.coverage(), one);
  sweep.addPosition(Vec2(std::numeric_limits<double>::infinity(), 0.0));
  for (int r = 0; r < 20; ++r) {
    for (int c = 0; c < 20; ++c) {
      if (inflated.isFree({c, r}))
        sweep.addPosition(inflated.cellCentre({c, r}));
    }
  }
  EXPECT_DOUBLE_EQ(sweep.coverage(), 1.0);
  EXPECT_THROW(CoverageSweep(raw, PlanningGrid::freeGrid(5, 5, 0.05), {1, 1}, 0.1),
               std::invalid_argument);
}

TEST(PlanningTasks, CoveragePreviewDrivesFromTheRobotIntoTheRegion) {
  const PlanningSettings settings;
  const PlanningGrids grids = gridsFromWorld(roomWithWall(), 0.16, settings);
  Box2 region;
  region.extend(Vec2(2.3, 0.2));
  region.extend(Vec2(3.8, 1.8));
  const CoveragePreview c = previewCoverage(grids, Pose2{1.0, 0.5, 0.0}, region,
                                            CoveragePattern::kSpiral, 0.25, settings, {});
  ASSERT_TRUE(c.ok) << c.error;
  EXPECT_TRUE(c.path.front().isApprox(Vec2(1.0, 0.5)));
  EXPECT_GE(c.approach.size(), 3u);  // round the wall
  EXPECT_GT(c.coverage.coverage, 0.9);
  EXPECT_FALSE(previewCoverage(grids, Pose2{1.0, 0.5, 0.0}, region, CoveragePattern::kSpiral, 0.0,
                               settings, {})
                   .ok);
}

}  // namespace
}  // namespace irgs::gui
