#include "core/sim/solid_raster.hpp"

#include <gtest/gtest.h>

#include "core/geometry/geometry_queries.hpp"
#include "core/sim/random.hpp"

namespace irgs {
namespace {

// 20 x 10 cells of 0.1 m from (-1, -0.5); a wall in column 15 (x in [0.5, 0.6)).
RasterMap wallRaster() {
  RasterMap r;
  r.width = 20;
  r.height = 10;
  r.resolution_m = 0.1;
  r.origin = {-1.0, -0.5, 0.0};
  r.cells.assign(200, RasterMap::kFree);
  for (int row = 0; row < r.height; ++row)
    r.at(15, row) = RasterMap::kOccupied;
  return r;
}

TEST(SolidRaster, CastFindsTheNearFaceOfTheFirstSolidCell) {
  const SolidRaster raster(wallRaster(), {});
  const auto hit = raster.cast({0.0, 0.01}, {1, 0}, 5.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance_m, 0.5, 1e-12);
  EXPECT_NEAR(hit->normal.x(), -1.0, 1e-12);
  EXPECT_NEAR(hit->normal.y(), 0.0, 1e-12);
  EXPECT_FALSE(raster.cast({0.0, 0.01}, {1, 0}, 0.45));
  EXPECT_FALSE(raster.cast({0.0, 0.01}, {-1, 0}, 5.0));  // leaves the raster: nothing there
  // The same through the RayCaster interface.
  const RasterCaster caster(raster);
  const RayCaster& any = caster;
  EXPECT_EQ(any.cast({0.0, 0.01}, {1, 0}, 5.0), hit);
}

TEST(SolidRaster, CastAtAnAngleMeetsTheWallWhereGeometrySays) {
  const SolidRaster raster(wallRaster(), {});
  const Vec2 dir = Vec2(1.0, 0.5).normalized();
  const auto hit = raster.cast({0.0, -0.3}, dir, 5.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance_m, 0.5 / dir.x(), 1e-12);
}

TEST(SolidRaster, CastEntersFromOutsideTheRaster) {
  const SolidRaster raster(wallRaster(), {});
  const auto hit = raster.cast({-3.0, 0.01}, {1, 0}, 10.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance_m, 3.5, 1e-12);
}

TEST(SolidRaster, UnknownCellsAreSolidByDefaultAndCanBeMadeFree) {
  RasterMap r = wallRaster();
  r.at(12, 5) = RasterMap::kUnknown;
  const SolidRaster solid_unknown(r, {});
  const auto hit = solid_unknown.cast({0.0, 0.05}, {1, 0}, 5.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance_m, 0.2, 1e-12);
  const SolidRaster free_unknown(r, {65, false});
  ASSERT_TRUE(free_unknown.cast({0.0, 0.05}, {1, 0}, 5.0));
  EXPECT_NEAR(free_unknown.cast({0.0, 0.05}, {1, 0}, 5.0)->distance_m, 0.5, 1e-12);
}

TEST(SolidRaster, OccupancyBelowTheThresholdIsFree) {
  RasterMap r = wallRaster();
  r.at(12, 5) = 50;
  EXPECT_FALSE(SolidRaster(r, {65, true}).solid(12, 5));
  EXPECT_TRUE(SolidRaster(r, {50, true}).solid(12, 5));
}

TEST(SolidRaster, StaircaseWallGetsItsSlantedNormal) {
  // A 45 degree wall drawn as a staircase of cells: the face the ray enters is axis-aligned,
  // but the reported normal follows the wall.
  RasterMap r;
  r.width = r.height = 40;
  r.resolution_m = 0.05;
  r.cells.assign(1600, RasterMap::kFree);
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      if (j >= 40 - i)
        r.at(i, j) = RasterMap::kOccupied;  // solid above the anti-diagonal
  const SolidRaster raster(r, {});
  const Vec2 dir = Vec2(1, 1).normalized();
  const auto hit = raster.cast({0.3, 0.3}, dir, 5.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->normal.dot(-dir), 1.0, 1e-9);
}

TEST(SolidRaster, PolygonOverlapAndContactQueries) {
  const SolidRaster raster(wallRaster(), {});
  const std::vector<Vec2> clear = {{0.2, -0.1}, {0.45, -0.1}, {0.45, 0.1}, {0.2, 0.1}};
  const std::vector<Vec2> touching = {{0.2, -0.1}, {0.5, -0.1}, {0.5, 0.1}, {0.2, 0.1}};
  EXPECT_FALSE(raster.polygonTouches(clear));
  EXPECT_TRUE(raster.polygonTouches(touching));
  EXPECT_TRUE(raster.segmentWithin({0.45, -0.1}, {0.45, 0.1}, 0.06));
  EXPECT_FALSE(raster.segmentWithin({0.45, -0.1}, {0.45, 0.1}, 0.04));
}

TEST(SolidRaster, ClearanceIsALowerBoundOfTheTrueDistance) {
  const SolidRaster raster(wallRaster(), {});
  for (double x = -1.5; x < 1.5; x += 0.037) {
    const Vec2 p(x, 0.013);
    // Distance to the wall occupying x in [0.5, 0.6].
    const double truth = x < 0.5 ? 0.5 - x : (x <= 0.6 ? 0.0 : x - 0.6);
    const double bound = raster.clearanceLowerBound(p, 10.0);
    EXPECT_LE(bound, truth + 1e-12) << x;
    if (x > -1.0 && x < 0.3) {
      EXPECT_GE(bound, truth - 0.15) << x;  // inside the raster: not uselessly small
    }
  }
  EXPECT_EQ(raster.clearanceLowerBound({-1.0, 0.0}, 0.2), 0.2);  // capped
}

// Reference: march along the ray in steps of 1/200 cell and report the first solid point.
std::optional<double> marchedDistance(const RasterMap& r, const SolidRaster& solid,
                                      const Vec2& origin, const Vec2& dir, double max_range) {
  const double step = r.resolution_m / 200.0;
  for (double t = 0.0; t <= max_range; t += step) {
    const Vec2 p = origin + t * dir;
    const double fx = (p.x() - r.origin.x) / r.resolution_m;
    const double fy = (p.y() - r.origin.y) / r.resolution_m;
    if (solid.solid(static_cast<int>(std::floor(fx)), static_cast<int>(std::floor(fy))))
      return t;
  }
  return std::nullopt;
}

TEST(SolidRaster, CastAgreesWithFineMarchingOnARandomRaster) {
  // Sparse random blocks leave wide open space, so the empty-space skipping is exercised.
  RasterMap r;
  r.width = 120;
  r.height = 90;
  r.resolution_m = 0.05;
  r.origin = {-2.0, -1.0, 0.0};
  r.cells.assign(static_cast<std::size_t>(r.width * r.height), RasterMap::kFree);
  SimRandom rng(77);
  for (int block = 0; block < 25; ++block) {
    const int c = static_cast<int>(rng.uniform() * 115),
              w = 1 + static_cast<int>(rng.uniform() * 5);
    const int row = static_cast<int>(rng.uniform() * 85),
              h = 1 + static_cast<int>(rng.uniform() * 5);
    for (int i = c; i < c + w; ++i)
      for (int j = row; j < row + h; ++j)
        r.at(i, j) = RasterMap::kOccupied;
  }
  const SolidRaster raster(r, {});
  int hits = 0;
  for (int ray = 0; ray < 300; ++ray) {
    const Vec2 origin(-2.5 + 7.0 * rng.uniform(), -1.5 + 5.5 * rng.uniform());
    const double angle = 2.0 * kPi * rng.uniform();
    const Vec2 dir(std::cos(angle), std::sin(angle));
    const auto hit = raster.cast(origin, dir, 5.0);
    const auto expected = marchedDistance(r, raster, origin, dir, 5.0);
    ASSERT_EQ(hit.has_value(), expected.has_value()) << ray;
    if (hit) {
      ++hits;
      EXPECT_NEAR(hit->distance_m, *expected, r.resolution_m / 100.0) << ray;
      EXPECT_NEAR(hit->normal.norm(), 1.0, 1e-12);
      EXPECT_LE(hit->normal.dot(dir), 0.0);  // facing the ray
    }
  }
  EXPECT_GT(hits, 50);
}

TEST(SolidRaster, RejectsAMalformedRaster) {
  RasterMap r = wallRaster();
  r.cells.pop_back();
  EXPECT_THROW(SolidRaster(r, {}), std::invalid_argument);
  RasterMap z = wallRaster();
  z.resolution_m = 0.0;
  EXPECT_THROW(SolidRaster(z, {}), std::invalid_argument);
}

TEST(GeometryQueries, SegmentAndPolygonPredicates) {
  EXPECT_TRUE(segmentsIntersect({0, 0}, {2, 0}, {1, -1}, {1, 1}));
  EXPECT_TRUE(segmentsIntersect({0, 0}, {2, 0}, {2, 0}, {3, 1}));  // touching ends
  EXPECT_FALSE(segmentsIntersect({0, 0}, {2, 0}, {3, -1}, {3, 1}));
  EXPECT_TRUE(segmentsIntersect({0, 0}, {2, 0}, {1, 0}, {3, 0}));  // collinear overlap
  const std::vector<Vec2> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_TRUE(pointInPolygon({0.5, 0.5}, square));
  EXPECT_FALSE(pointInPolygon({1.5, 0.5}, square));
  EXPECT_TRUE(polygonTouchesSegment(square, {0.2, 0.2}, {0.3, 0.3}));  // wholly inside
  EXPECT_FALSE(polygonTouchesSegment(square, {2, 0}, {2, 1}));
  Box2 box;
  box.extend(Vec2(0.25, 0.25));
  box.extend(Vec2(0.5, 0.5));
  EXPECT_TRUE(polygonTouchesBox(square, box));  // wholly inside
  EXPECT_DOUBLE_EQ(segmentSegmentDistance({0, 0}, {1, 0}, {0, 2}, {1, 2}), 2.0);
  EXPECT_DOUBLE_EQ(pointBoxDistance({3, 4}, {{0, 0}, {0, 0}}), 5.0);
}

}  // namespace
}  // namespace irgs
