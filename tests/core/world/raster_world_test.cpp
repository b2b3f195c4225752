#include "core/world/raster_world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace irgs {
namespace {

RasterMap freeRaster(int w, int h, double res, Pose2 origin = {}) {
  RasterMap r;
  r.width = w;
  r.height = h;
  r.resolution_m = res;
  r.origin = origin;
  r.cells.assign(static_cast<std::size_t>(w * h), RasterMap::kFree);
  return r;
}

// Clearance of a free cell by brute force over every blocking cell (same definition as the
// implementation: centre to the blocking cell's edge, capped by the raster edge).
double bruteClearance(const RasterMap& r, int col, int row) {
  double best = std::min({col + 0.5, r.width - col - 0.5, row + 0.5, r.height - row - 0.5});
  for (int y = 0; y < r.height; ++y) {
    for (int x = 0; x < r.width; ++x) {
      if (!isFreeCell(r.at(x, y)))
        best = std::min(best, std::hypot(x - col, y - row) - 0.5);
    }
  }
  return best * r.resolution_m;
}

TEST(RasterWorld, OpenRasterStartsAtTheNearestCellWithClearance) {
  // Origin at the lower-left corner: the first cell 0.25 m from every edge is (2, 2).
  const StartPoseSearch s = findStartPose(freeRaster(10, 10, 0.1), 0.25);
  EXPECT_TRUE(s.found);
  EXPECT_NEAR(s.pose.x, 0.25, 1e-12);
  EXPECT_NEAR(s.pose.y, 0.25, 1e-12);
  EXPECT_NEAR(s.clearance_m, 0.25, 1e-12);
}

TEST(RasterWorld, ObstacleAtTheOriginPushesTheStartAway) {
  RasterMap r = freeRaster(40, 40, 0.1, {-2.0, -2.0, 0.0});
  // Occupied 0.6 m square around the world origin: cells 17..22.
  for (int y = 17; y < 23; ++y)
    for (int x = 17; x < 23; ++x)
      r.at(x, y) = RasterMap::kOccupied;
  const StartPoseSearch s = findStartPose(r, 0.25);
  ASSERT_TRUE(s.found);
  const auto cell = r.worldToCell(s.pose.position());
  ASSERT_TRUE(cell);
  EXPECT_GE(bruteClearance(r, cell->first, cell->second), 0.25 - 1e-9);
  // Nearest such cell: 0.3 m half-width + 0.25 m clearance -> centre at 0.55 m from the axis.
  EXPECT_NEAR(std::max(std::abs(s.pose.x), std::abs(s.pose.y)), 0.55, 1e-9);
}

TEST(RasterWorld, UnknownCellsBlockLikeWalls) {
  RasterMap r = freeRaster(10, 1, 1.0);
  r.at(3, 0) = RasterMap::kUnknown;
  EXPECT_FALSE(isFreeCell(RasterMap::kUnknown));
  EXPECT_FALSE(isFreeCell(50));
  EXPECT_TRUE(isFreeCell(49));
  // A single row is only 0.5 m from its edges: nothing qualifies for 0.6 m.
  const StartPoseSearch s = findStartPose(r, 0.6);
  EXPECT_FALSE(s.found);
  EXPECT_NEAR(s.clearance_m, 0.5, 1e-12);  // the most open cell is still returned
}

TEST(RasterWorld, NoFreeCellGivesTheRasterCentre) {
  RasterMap r = freeRaster(4, 2, 0.5, {1.0, 1.0, 0.0});
  std::fill(r.cells.begin(), r.cells.end(), RasterMap::kOccupied);
  const StartPoseSearch s = findStartPose(r);
  EXPECT_FALSE(s.found);
  EXPECT_NEAR(s.pose.x, 2.0, 1e-12);
  EXPECT_NEAR(s.pose.y, 1.5, 1e-12);
}

TEST(RasterWorld, DistanceTransformAgreesWithBruteForceOnRandomRasters) {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 40; ++trial) {
    const int w = 5 + static_cast<int>(rng() % 30), h = 5 + static_cast<int>(rng() % 30);
    RasterMap r = freeRaster(w, h, 0.05, {-0.6, -0.4, 0.0});
    const int blocked = static_cast<int>(rng() % 12);
    for (int i = 0; i < blocked; ++i) {
      r.at(static_cast<int>(rng() % static_cast<unsigned>(w)),
           static_cast<int>(rng() % static_cast<unsigned>(h))) =
          (i % 2) ? RasterMap::kOccupied : RasterMap::kUnknown;
    }
    const double clearance = 0.05 * (1 + static_cast<int>(rng() % 4));
    // Expected: the qualifying free cell nearest the origin, first in row-major order on ties.
    double best = std::numeric_limits<double>::infinity();
    int best_col = -1, best_row = -1;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        if (!isFreeCell(r.at(x, y)) || bruteClearance(r, x, y) < clearance - 1e-9)
          continue;
        const double d = r.cellCentre(x, y).squaredNorm();
        if (d < best) {
          best = d;
          best_col = x;
          best_row = y;
        }
      }
    }
    const StartPoseSearch s = findStartPose(r, clearance);
    ASSERT_EQ(s.found, best_col >= 0) << "trial " << trial;
    if (s.found) {
      const Vec2 c = r.cellCentre(best_col, best_row);
      EXPECT_NEAR(s.pose.x, c.x(), 1e-12) << "trial " << trial;
      EXPECT_NEAR(s.pose.y, c.y(), 1e-12) << "trial " << trial;
      EXPECT_NEAR(s.clearance_m, bruteClearance(r, best_col, best_row), 1e-9);
    }
  }
}

TEST(RasterWorld, WorldFromRasterKeepsTheRasterAndNamesTheMap) {
  StartPoseSearch search;
  const WorldMap world = worldFromRaster(freeRaster(20, 20, 0.1), "maps/lab.yaml", 0.25, &search);
  EXPECT_EQ(world.name, "lab");
  ASSERT_TRUE(world.raster);
  EXPECT_EQ(world.raster->source, "maps/lab.yaml");
  EXPECT_EQ(world.raster->raster.width, 20);
  EXPECT_TRUE(search.found);
  EXPECT_EQ(world.start, search.pose);
  EXPECT_TRUE(world.walls.empty());
}

}  // namespace
}  // namespace irgs
