#include "core/editing/vectorise.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace irgs::editing {
namespace {

RasterMap blank(int w, int h, double res = 0.1, Pose2 origin = {}) {
  RasterMap r;
  r.width = w;
  r.height = h;
  r.resolution_m = res;
  r.origin = origin;
  r.cells.assign(static_cast<std::size_t>(w * h), RasterMap::kFree);
  return r;
}

void fill(RasterMap& r, int c0, int r0, int c1, int r1, std::int8_t v = RasterMap::kOccupied) {
  for (int row = r0; row <= r1; ++row)
    for (int col = c0; col <= c1; ++col)
      r.at(col, row) = v;
}

double signedArea(const std::vector<Vec2>& loop) {
  double a = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i)
    a += cross(loop[i], loop[(i + 1) % loop.size()]);
  return 0.5 * a;
}

TEST(Vectorise, ABlockBecomesItsFourCornersCounterClockwiseInWorldMetres) {
  RasterMap r = blank(10, 10, 0.1, Pose2{1.0, 2.0, 0.0});
  fill(r, 2, 3, 5, 5);  // cols 2..5, rows 3..5
  const auto outlines = traceOccupiedOutlines(r);
  ASSERT_EQ(outlines.size(), 1u);
  const auto& o = outlines[0];
  ASSERT_EQ(o.size(), 4u);
  EXPECT_NEAR(o[0].x(), 1.2, 1e-12);
  EXPECT_NEAR(o[0].y(), 2.3, 1e-12);
  Box2 box;
  for (const Vec2& p : o)
    box.extend(p);
  EXPECT_NEAR(box.min.x(), 1.2, 1e-12);
  EXPECT_NEAR(box.max.x(), 1.6, 1e-12);
  EXPECT_NEAR(box.min.y(), 2.3, 1e-12);
  EXPECT_NEAR(box.max.y(), 2.6, 1e-12);
  EXPECT_NEAR(signedArea(o), 0.4 * 0.3, 1e-12);  // counter-clockwise
}

TEST(Vectorise, ARoomOutlineGivesItsOuterAndInnerFaces) {
  RasterMap r = blank(20, 20);
  fill(r, 2, 2, 17, 17);
  fill(r, 4, 4, 15, 15, RasterMap::kFree);  // a 2-cell thick wall around a free room
  const auto outlines = traceOccupiedOutlines(r);
  ASSERT_EQ(outlines.size(), 2u);
  EXPECT_EQ(outlines[0].size(), 4u);
  EXPECT_EQ(outlines[1].size(), 4u);
  EXPECT_NEAR(signedArea(outlines[0]), 1.6 * 1.6, 1e-9);   // outer face, CCW
  EXPECT_NEAR(signedArea(outlines[1]), -1.2 * 1.2, 1e-9);  // inner face (the hole), CW
}

TEST(Vectorise, DiagonalNeighboursStayApartAndSpeckleIsDropped) {
  RasterMap r = blank(10, 10);
  fill(r, 2, 2, 4, 4);
  fill(r, 5, 5, 7, 7);  // touches the first block at one corner only
  fill(r, 0, 9, 0, 9);  // a single-cell speckle
  VectoriseSettings fine;
  fine.min_size_m = 0.05;
  EXPECT_EQ(traceOccupiedOutlines(r, fine).size(), 3u);
  const auto outlines = traceOccupiedOutlines(r);  // default: smaller than 3 cells is dropped
  ASSERT_EQ(outlines.size(), 2u);
  for (const auto& o : outlines)
    EXPECT_EQ(o.size(), 4u);
  // Unknown cells are not walls; cells at the threshold are.
  RasterMap u = blank(6, 6);
  fill(u, 1, 1, 4, 4, RasterMap::kUnknown);
  EXPECT_TRUE(traceOccupiedOutlines(u).empty());
  fill(u, 1, 1, 4, 4, 65);
  EXPECT_EQ(traceOccupiedOutlines(u).size(), 1u);
}

TEST(Vectorise, ASlantedWallLosesItsStaircaseWithinTheTolerance) {
  RasterMap r = blank(60, 60);
  // A band 3 cells thick along y = x / 2 (a 26.6 degree wall).
  for (int c = 5; c < 55; ++c)
    for (int d = 0; d < 3; ++d)
      r.at(c, c / 2 + d) = RasterMap::kOccupied;
  const auto outlines = traceOccupiedOutlines(r);
  ASSERT_EQ(outlines.size(), 1u);
  EXPECT_LE(outlines[0].size(), 8u);  // from ~100 staircase corners
  EXPECT_GE(outlines[0].size(), 4u);
  for (const Vec2& p : outlines[0]) {  // every kept corner is near the band's faces
    const double along_line = p.y() - 0.5 * p.x();
    EXPECT_GT(along_line, -0.15);
    EXPECT_LT(along_line, 0.45);
  }
}

TEST(Vectorise, TheEditAddsClosedWallsAndUndoes) {
  WorldMap map;
  Wall existing;
  existing.id = "raster-1";  // taken: the new walls get other ids
  existing.points = {Vec2(0, 0), Vec2(1, 0)};
  map.walls.push_back(existing);
  EXPECT_TRUE(vectoriseRaster(map).empty());  // no raster: nothing to do
  RasterLayer layer;
  layer.raster = blank(20, 20);
  fill(layer.raster, 2, 2, 6, 6);
  fill(layer.raster, 10, 10, 15, 12);
  map.raster = layer;
  const Edit edit = vectoriseRaster(map);
  ASSERT_EQ(edit.changes.size(), 2u);
  ASSERT_EQ(edit.selection_after.size(), 2u);
  WorldMap edited = map;
  applyEdit(edited, edit);
  ASSERT_EQ(edited.walls.size(), 3u);
  EXPECT_TRUE(edited.walls[1].closed);
  EXPECT_EQ(edited.walls[1].id, "raster-2");
  EXPECT_EQ(edited.walls[2].id, "raster-3");
  EXPECT_EQ(edit.selection_after[1], (ElementRef{ElementKind::kWall, 2}));
  revertEdit(edited, edit);
  ASSERT_EQ(edited.walls.size(), 1u);
  EXPECT_EQ(edited.walls[0].id, "raster-1");
}

TEST(Vectorise, BadInputThrows) {
  RasterMap r = blank(4, 4);
  r.cells.pop_back();
  EXPECT_THROW(traceOccupiedOutlines(r), std::invalid_argument);
  r = blank(4, 4, 0.0);
  EXPECT_THROW(traceOccupiedOutlines(r), std::invalid_argument);
  VectoriseSettings bad;
  bad.tolerance_m = -1.0;
  EXPECT_THROW(traceOccupiedOutlines(blank(4, 4), bad), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::editing

namespace irgs::editing {
namespace {

TEST(RasterLayerEdit, ImportingALayerReplacesTheOldOneAndUndoRestoresIt) {
  WorldMap map;
  Wall wall;
  wall.id = "w";
  wall.points = {Vec2(0, 0), Vec2(1, 0)};
  map.walls.push_back(wall);
  RasterLayer first;
  first.source = "first.yaml";
  first.raster = blank(4, 4);
  RasterLayer second;
  second.source = "second.yaml";
  second.raster = blank(8, 2);

  const Edit add = setRasterLayer(map, first);
  EXPECT_FALSE(add.empty());
  applyEdit(map, add);
  ASSERT_TRUE(map.raster.has_value());
  EXPECT_EQ(map.raster->source, "first.yaml");
  const Edit replace = setRasterLayer(map, second);
  applyEdit(map, replace);
  EXPECT_EQ(map.raster->raster.width, 8);
  EXPECT_EQ(map.walls.size(), 1u);  // the vectors are untouched
  revertEdit(map, replace);
  EXPECT_EQ(map.raster->source, "first.yaml");
  const Edit remove = setRasterLayer(map, std::nullopt);
  applyEdit(map, remove);
  EXPECT_FALSE(map.raster.has_value());
  revertEdit(map, remove);
  revertEdit(map, add);
  EXPECT_FALSE(map.raster.has_value());

  RasterLayer broken;
  broken.raster = blank(4, 4);
  broken.raster.cells.pop_back();
  EXPECT_THROW(setRasterLayer(map, broken), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::editing
