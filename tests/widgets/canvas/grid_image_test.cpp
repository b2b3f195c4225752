#include "widgets/canvas/grid_image.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace irgs::widgets {
namespace {

// A grid observed by one sonar looking up (+y): asymmetric in y, so a row flip shows.
OccupancyGrid upwardCone() {
  OccupancyGrid grid(0.01);
  const SonarInverseModel model;
  for (int i = 0; i < 4; ++i)
    grid.integrateSonar({0.0, 0.0}, kPi / 2, degToRad(40.0), 1.0, true, model);
  return grid;
}

TEST(GridToImage, ColoursUnknownTransparentFreeLightOccupiedDark) {
  const OccupancyGrid grid = upwardCone();
  OccupancyGrid::CellRect rect = grid.observedCellRect();
  ASSERT_FALSE(rect.empty());
  rect.col0 -= 3;  // a margin of never-observed cells
  rect.row0 -= 3;
  rect.col1 += 3;
  rect.row1 += 3;
  const QImage image = gridToImage(grid, rect);
  ASSERT_EQ(image.width(), rect.width());
  ASSERT_EQ(image.height(), rect.height());

  int free_cells = 0, occupied_cells = 0, unknown_cells = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const Cell cell{rect.col0 + x, rect.row1 - y};  // image top = largest row
      const QRgb px = image.pixel(x, y);
      if (!grid.observed(cell)) {
        EXPECT_EQ(qAlpha(px), 0) << x << "," << y;
        ++unknown_cells;
        continue;
      }
      EXPECT_EQ(qAlpha(px), 255);
      const double p = grid.probability(cell);
      if (p < 0.3) {
        EXPECT_GT(qGray(px), 200) << "free cell drawn dark at " << x << "," << y;
        ++free_cells;
      } else if (p > 0.7) {
        EXPECT_LT(qGray(px), 90) << "occupied cell drawn light at " << x << "," << y;
        ++occupied_cells;
      }
    }
  }
  EXPECT_GT(free_cells, 20);
  EXPECT_GT(occupied_cells, 5);
  EXPECT_GT(unknown_cells, 20);
}

TEST(GridToImage, TopRowIsTheLargestY) {
  const OccupancyGrid grid = upwardCone();
  // The arc at y = 1 m lies in the upper part of the image, the apex at the bottom.
  const OccupancyGrid::CellRect rect{-50, -20, 50, 120};
  const QImage image = gridToImage(grid, rect);
  const Cell arc = grid.cellAt({0.0, 1.0});
  const Cell below = grid.cellAt({0.0, -1.0});
  ASSERT_GE(arc.row, rect.row0);
  ASSERT_LE(arc.row, rect.row1);
  // Find the darkest pixel of the centre column: it is at the arc's row counted from the top.
  int darkest_y = -1, darkest = 256;
  for (int y = 0; y < image.height(); ++y) {
    const QRgb px = image.pixel(arc.col - rect.col0, y);
    if (qAlpha(px) == 255 && qGray(px) < darkest) {
      darkest = qGray(px);
      darkest_y = y;
    }
  }
  EXPECT_NEAR(darkest_y, rect.row1 - arc.row, 2);
  EXPECT_LT(darkest, 90);
  EXPECT_FALSE(grid.observed(below));
}

TEST(GridToImage, EmptyRectGivesANullImage) {
  const OccupancyGrid grid = upwardCone();
  EXPECT_TRUE(gridToImage(grid, {}).isNull());
  EXPECT_TRUE(gridToImage(grid, {5, 5, 4, 9}).isNull());
}

TEST(RasterToImage, FlipsRowsAndColoursValues) {
  RasterMap raster;
  raster.width = 3;
  raster.height = 2;
  raster.cells = {0,  100, -1,  // row 0: smallest y -> bottom image row
                  50, 0,   0};  // row 1
  const QImage image = rasterToImage(raster);
  ASSERT_EQ(image.size(), QSize(3, 2));
  EXPECT_EQ(qAlpha(image.pixel(0, 1)), 0);    // free: transparent
  EXPECT_EQ(qAlpha(image.pixel(1, 1)), 255);  // occupied: opaque and dark
  EXPECT_LT(qGray(image.pixel(1, 1)), 90);
  EXPECT_GT(qAlpha(image.pixel(2, 1)), 0);  // unknown: translucent grey
  EXPECT_LT(qAlpha(image.pixel(2, 1)), 255);
  EXPECT_GT(qAlpha(image.pixel(0, 0)), 100);  // 50 %: half way
  EXPECT_LT(qAlpha(image.pixel(0, 0)), 155);
}

TEST(RasterToImage, InconsistentRasterGivesANullImage) {
  RasterMap raster;
  raster.width = 3;
  raster.height = 2;
  raster.cells = {0, 0};
  EXPECT_TRUE(rasterToImage(raster).isNull());
  EXPECT_TRUE(rasterToImage(RasterMap{}).isNull());
}

}  // namespace
}  // namespace irgs::widgets
