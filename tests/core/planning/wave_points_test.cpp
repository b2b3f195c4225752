#include "core/planning/wave_points.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>

#include "core/planning/free_space.hpp"
#include "core/world/map_file.hpp"

namespace irgs {
namespace {

TEST(WavePoints, RegionPathsAreFreeConnectedAndFoundWheneverDijkstraFindsOne) {
  std::mt19937_64 rng(99);
  int found = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int w = 30 + trial % 31, h = 25 + (trial * 3) % 29;
    PlanningGrid g = PlanningGrid::freeGrid(w, h, 0.05);
    std::uniform_int_distribution<int> col(0, w - 1), row(0, h - 1), side(1, 5);
    while (g.blockedCount() < g.cellCount() / 5) {
      const int c0 = col(rng), r0 = row(rng), cw = side(rng), rh = side(rng);
      for (int r = r0; r < std::min(h, r0 + rh); ++r)
        for (int c = c0; c < std::min(w, c0 + cw); ++c)
          g.setBlocked({c, r}, true);
    }
    const PlanningGrid inflated = inflate(g, 0.03);
    const WaveRegions regions = partitionIntoBlocks(inflated, 8 + trial % 5);
    for (int q = 0; q < 5; ++q) {
      const Cell s{col(rng), row(rng)}, t{col(rng), row(rng)};
      const PlanResult ref = dijkstraReference(inflated, s, t);
      const WavePlan p = planWithWavePoints(inflated, regions, s, t);
      ASSERT_EQ(p.status, ref.status) << trial;
      if (!ref.found())
        continue;
      ++found;
      EXPECT_GE(p.cost, ref.cost);
      ASSERT_EQ(p.cells.front(), s);
      ASSERT_EQ(p.cells.back(), t);
      EXPECT_TRUE(polylineIsFree(inflated, p.points));  // collision-free with the inflated robot
      for (const std::size_t wi : p.wave_indices)
        ASSERT_LT(wi, p.cells.size());
    }
  }
  EXPECT_GT(found, 40);
}

TEST(WavePoints, EntrancesJoinDifferentRegionsAcrossBlockBorders) {
  const PlanningGrid g = PlanningGrid::freeGrid(20, 10, 0.1);
  const WaveRegions r = partitionIntoBlocks(g, 10);
  EXPECT_EQ(r.region_count, 2);
  ASSERT_EQ(r.entrances.size(), 1u);  // one run along the shared border, one wave point
  EXPECT_NE(r.entrances[0].region_a, r.entrances[0].region_b);
  EXPECT_EQ(r.entrances[0].a.col, 9);
  EXPECT_EQ(r.entrances[0].b.col, 10);
  const WavePlan p = planWithWavePoints(g, r, {1, 1}, {18, 8});
  ASSERT_TRUE(p.found());
  ASSERT_EQ(p.wave_indices.size(), 1u);
  EXPECT_EQ(p.cells[p.wave_indices[0]], r.entrances[0].a);
  EXPECT_THROW(partitionIntoBlocks(g, 1), std::invalid_argument);
}

TEST(WavePoints, UserWavePointsAreVisitedInOrder) {
  const PlanningGrid g = PlanningGrid::freeGrid(30, 30, 0.1);
  const WavePlan p = planThroughWavePoints(g, {0, 0}, {29, 0}, {{15, 20}, {20, 5}});
  ASSERT_TRUE(p.found());
  ASSERT_EQ(p.wave_indices.size(), 2u);
  EXPECT_EQ(p.cells[p.wave_indices[0]], (Cell{15, 20}));
  EXPECT_EQ(p.cells[p.wave_indices[1]], (Cell{20, 5}));
  PlanningGrid b = g;
  b.setBlocked({15, 20}, true);
  EXPECT_EQ(planThroughWavePoints(b, {0, 0}, {29, 0}, {{15, 20}}).status, PlanStatus::kGoalBlocked);
}

// Two 4 m x 4 m rooms side by side, joined by a door in the wall x = 4 from y = door_y0 to
// door_y1.
WorldMap twoRooms(double door_y0, double door_y1) {
  WorldMap map;
  map.walls.push_back({"outer", {{0.0, 0.0}, {8.0, 0.0}, {8.0, 4.0}, {0.0, 4.0}}, true, {}});
  map.walls.push_back({"lower", {{4.0, 0.0}, {4.0, door_y0}}, false, {}});
  map.walls.push_back({"upper", {{4.0, door_y1}, {4.0, 4.0}}, false, {}});
  return map;
}

PlanningGrid wallsOnly(const WorldMap& map) {
  return planningGridFromWorld(map, 0.05, PlanningGridOptions{}, 0.1);
}

TEST(Doorways, TheDoorBetweenTwoRoomsIsTheOnlyDoorway) {
  const PlanningGrid grid = wallsOnly(twoRooms(1.5, 2.4));
  const std::vector<Doorway> doors = detectDoorways(grid);
  ASSERT_EQ(doors.size(), 1u);
  EXPECT_LT((doors[0].centre - Vec2(4.0, 1.95)).norm(), 0.1);
  // The walls are rasterised a cell thick, so the free width is the door less up to a cell.
  EXPECT_NEAR(doors[0].width_m, 0.85, 0.06);
  EXPECT_NEAR(doors[0].direction_rad, kPi / 2.0, degToRad(10.0));
  EXPECT_LT(std::abs(doors[0].jamb_a.x() - 4.0), 0.1);
  EXPECT_LT(std::abs(doors[0].jamb_b.x() - 4.0), 0.1);
  EXPECT_NEAR((doors[0].jamb_b - doors[0].jamb_a).norm(), doors[0].width_m, 1e-9);
  EXPECT_TRUE(grid.isFree(doors[0].cell));
}

TEST(Doorways, PassagesNarrowerThanTheRobotOrWiderThanADoorAreNoDoorways) {
  DoorwayOptions options;
  options.min_width_m = 0.3;
  options.max_width_m = 1.2;
  EXPECT_TRUE(detectDoorways(wallsOnly(twoRooms(1.8, 2.05)), options).empty());  // 0.25 m
  EXPECT_TRUE(detectDoorways(wallsOnly(twoRooms(1.0, 2.8)), options).empty());   // 1.8 m
  EXPECT_EQ(detectDoorways(wallsOnly(twoRooms(1.5, 2.2)), options).size(), 1u);  // 0.7 m
  EXPECT_TRUE(detectDoorways(PlanningGrid::freeGrid(20, 20, 0.05)).empty());
  EXPECT_TRUE(detectDoorways(PlanningGrid{}).empty());
}

TEST(Doorways, RoomsSplitAtTheDoorAndPlansCrossItsWavePoint) {
  const PlanningGrid walls = wallsOnly(twoRooms(1.5, 2.4));
  const std::vector<Doorway> doors = detectDoorways(walls);
  ASSERT_EQ(doors.size(), 1u);
  const PlanningGrid inflated = inflate(walls, 0.15);
  const WaveRegions regions = partitionAtDoorways(inflated, doors);
  EXPECT_EQ(regions.block_cells, 0);
  ASSERT_EQ(regions.region_count, 2);
  ASSERT_EQ(regions.entrances.size(), 1u);
  EXPECT_EQ(regions.entrances[0].a, doors[0].cell);
  EXPECT_NE(regions.entrances[0].region_a, regions.entrances[0].region_b);
  // Every free cell left of the wall is in one region, every one right of it in the other.
  const auto left = regions.region_of_cell[inflated.index(*inflated.worldToCell({1.0, 1.0}))];
  const auto right = regions.region_of_cell[inflated.index(*inflated.worldToCell({7.0, 3.0}))];
  EXPECT_NE(left, right);
  for (int r = 0; r < inflated.height; ++r)
    for (int c = 0; c < inflated.width; ++c) {
      if (!inflated.isFree({c, r}))
        continue;
      const double x = inflated.cellCentre({c, r}).x();
      const auto region = regions.region_of_cell[inflated.index({c, r})];
      if (x < 3.7) {
        ASSERT_EQ(region, left);
      } else if (x > 4.3) {
        ASSERT_EQ(region, right);
      }
    }
  const Cell s = *inflated.worldToCell({1.0, 1.0}), t = *inflated.worldToCell({7.0, 3.0});
  const WavePlan plan = planWithWavePoints(inflated, regions, s, t);
  ASSERT_TRUE(plan.found());
  ASSERT_EQ(plan.wave_indices.size(), 1u);
  EXPECT_EQ(plan.cells[plan.wave_indices[0]], doors[0].cell);
  EXPECT_TRUE(polylineIsFree(inflated, plan.points));
  const PlanResult ref = dijkstraReference(inflated, s, t);
  ASSERT_TRUE(ref.found());
  EXPECT_GE(plan.cost, ref.cost);
  EXPECT_LT(static_cast<double>(plan.cost), 1.05 * static_cast<double>(ref.cost));
}

TEST(Doorways, ADoorTheInflatedRobotDoesNotFitThroughAddsNoEntrance) {
  const PlanningGrid walls = wallsOnly(twoRooms(1.6, 2.0));  // 0.4 m, robot 0.5 m wide
  const std::vector<Doorway> doors = detectDoorways(walls);
  ASSERT_EQ(doors.size(), 1u);
  const WaveRegions regions = partitionAtDoorways(inflate(walls, 0.25), doors);
  EXPECT_TRUE(regions.entrances.empty());
  EXPECT_EQ(regions.region_count, 2);
}

TEST(Doorways, EveryDoorOfTheBundledApartmentIsFound) {
  const MapLoadResult loaded =
      loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/default.json");
  ASSERT_TRUE(loaded.map.has_value());
  const PlanningGrid grid = wallsOnly(*loaded.map);
  const std::vector<Doorway> doors = detectDoorways(grid);
  // Door centres from the wall gaps of default.json.
  for (const Vec2& door :
       {Vec2(1.7, 3.5), Vec2(4.1, 3.5), Vec2(5.0, 1.5), Vec2(5.0, 4.7), Vec2(3.0, 4.8)}) {
    double nearest = 1e9;
    for (const Doorway& d : doors)
      nearest = std::min(nearest, (d.centre - door).norm());
    EXPECT_LT(nearest, 0.15) << door.transpose();
  }
  const WaveRegions regions = partitionAtDoorways(inflate(grid, 0.15), doors);
  EXPECT_GE(regions.entrances.size(), 5u);
}

TEST(Doorways, InvalidOptionsThrow) {
  const PlanningGrid grid = wallsOnly(twoRooms(1.5, 2.4));
  DoorwayOptions o;
  o.min_width_m = 2.0;  // above max
  EXPECT_TRUE(doorwayOptionsError(o).has_value());
  EXPECT_THROW(detectDoorways(grid, o), std::invalid_argument);
  o = {};
  o.open_ratio = 1.0;
  EXPECT_THROW(detectDoorways(grid, o), std::invalid_argument);
  o = {};
  o.directions = 2;
  EXPECT_THROW(detectDoorways(grid, o), std::invalid_argument);
  EXPECT_FALSE(doorwayOptionsError({}).has_value());
  Doorway outside;
  outside.cell = {-1, 0};
  EXPECT_THROW(partitionAtDoorways(grid, {outside}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
