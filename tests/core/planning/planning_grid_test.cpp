#include "core/planning/planning_grid.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/planning/distance_transform.hpp"

namespace irgs {
namespace {

TEST(DistanceTransform, MatchesBruteForceOnRandomGrids) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 60; ++trial) {
    const int w = 1 + trial % 23, h = 1 + (trial * 5) % 19;
    std::vector<std::uint8_t> src(static_cast<std::size_t>(w * h));
    std::bernoulli_distribution on(trial % 3 == 0 ? 0.02 : 0.2);
    for (auto& s : src)
      s = on(rng) ? 1 : 0;
    const std::vector<double> d = squaredDistanceTransform(src, w, h);
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c) {
        double best = kNoSource;
        for (int r2 = 0; r2 < h; ++r2)
          for (int c2 = 0; c2 < w; ++c2)
            if (src[static_cast<std::size_t>(r2 * w + c2)] != 0)
              best = std::min(best, double((c - c2) * (c - c2) + (r - r2) * (r - r2)));
        ASSERT_EQ(d[static_cast<std::size_t>(r * w + c)], best) << trial << " " << c << "," << r;
      }
  }
  EXPECT_THROW(squaredDistanceTransform(std::vector<std::uint8_t>(3), 2, 2), std::invalid_argument);
}

TEST(PlanningGrid, InflationBlocksExactlyTheCellsWithinRadiusPlusHalfACell) {
  PlanningGrid g = PlanningGrid::freeGrid(21, 21, 0.1);
  g.setBlocked({10, 10}, true);
  const PlanningGrid in = inflate(g, 0.25);  // reach 2.5 + 0.5 = 3 cells
  for (int r = 0; r < 21; ++r)
    for (int c = 0; c < 21; ++c) {
      const int d2 = (c - 10) * (c - 10) + (r - 10) * (r - 10);
      EXPECT_EQ(!in.isFree({c, r}), d2 <= 9) << c << "," << r;
    }
  EXPECT_TRUE(in.isFree({13, 11}));   // d² = 10: a disc, not a square kernel
  EXPECT_FALSE(in.isFree({13, 10}));  // d = 3
  EXPECT_EQ(inflate(g, 0.0), g);
  EXPECT_THROW(inflate(g, NAN), std::invalid_argument);
}

TEST(PlanningGrid, FromRasterUsesThresholdAndUnknownPolicy) {
  RasterMap m;
  m.width = 3;
  m.height = 1;
  m.resolution_m = 0.5;
  m.origin = {1.0, 2.0, 0.0};
  m.cells = {0, 100, -1};
  PlanningGridOptions o;
  PlanningGrid g = planningGridFromRaster(m, o);
  EXPECT_TRUE(g.isFree({0, 0}));
  EXPECT_FALSE(g.isFree({1, 0}));
  EXPECT_FALSE(g.isFree({2, 0}));
  EXPECT_EQ(g.origin, Vec2(1.0, 2.0));
  o.unknown_is_blocked = false;
  EXPECT_TRUE(planningGridFromRaster(m, o).isFree({2, 0}));
  ASSERT_TRUE(g.worldToCell({1.6, 2.1}).has_value());
  EXPECT_EQ(*g.worldToCell({1.6, 2.1}), (Cell{1, 0}));
  EXPECT_FALSE(g.worldToCell({0.9, 2.1}).has_value());
  m.cells.pop_back();
  EXPECT_THROW(planningGridFromRaster(m, o), std::invalid_argument);
  o.robot_radius_m = -1.0;
  EXPECT_THROW(planningGridFromRaster(m, o), std::invalid_argument);
}

TEST(PlanningGrid, FromOccupancyBlocksLikelyOccupiedAndUnknownCells) {
  OccupancyGrid occ(0.1);
  SonarInverseModel model;
  for (int k = 0; k < 5; ++k)
    occ.integrateSonar({0.05, 0.05}, 0.0, degToRad(20.0), 1.0, true, model);
  PlanningGridOptions o;
  const PlanningGrid g = planningGridFromOccupancy(occ, o, 1);
  ASSERT_FALSE(g.empty());
  const auto near = g.worldToCell({0.45, 0.05});
  const auto hit = g.worldToCell({1.0, 0.05});
  const auto outside = g.worldToCell(g.origin + Vec2(0.01, 0.01));  // margin: never observed
  ASSERT_TRUE(near && hit && outside);
  EXPECT_TRUE(g.isFree(*near));
  EXPECT_FALSE(g.isFree(*hit));
  EXPECT_FALSE(g.isFree(*outside));
  EXPECT_TRUE(planningGridFromOccupancy(OccupancyGrid(0.1), o).empty());
}

TEST(PlanningGrid, FromWorldRasterisesWallsAndFillsObstacles) {
  WorldMap map;
  map.walls.push_back({"w", {{0.0, 0.0}, {2.0, 0.0}, {2.0, 2.0}, {0.0, 2.0}}, true, {}});
  map.obstacles.push_back({"o", {{0.8, 0.8}, {1.2, 0.8}, {1.2, 1.2}, {0.8, 1.2}}, {}});
  PlanningGridOptions o;
  const PlanningGrid g = planningGridFromWorld(map, 0.05, o, 0.1);
  const auto at = [&g](double x, double y) { return g.isFree(*g.worldToCell({x, y})); };
  EXPECT_FALSE(at(1.0, 0.01));  // wall
  EXPECT_FALSE(at(1.0, 1.0));   // obstacle interior
  EXPECT_TRUE(at(0.4, 0.4));
  o.robot_radius_m = 0.2;
  const PlanningGrid in = planningGridFromWorld(map, 0.05, o, 0.1);
  const auto in_at = [&in](double x, double y) { return in.isFree(*in.worldToCell({x, y})); };
  EXPECT_FALSE(in_at(0.4, 0.15));  // 0.15 m from the wall < radius
  EXPECT_TRUE(in_at(0.4, 0.4));
  EXPECT_THROW(planningGridFromWorld(WorldMap{}, 0.05, o), std::invalid_argument);
  EXPECT_THROW(planningGridFromWorld(map, 0.0, o), std::invalid_argument);
  EXPECT_THROW(planningGridFromWorld(map, 1e-9, o), std::invalid_argument);  // too many cells
}

}  // namespace
}  // namespace irgs
