#include "core/mapping/grid_export.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "core/world/ros_map.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;

// A grid with a free square (0..0.5 m)² and an occupied wall column at x = 0.5 .. 0.55 m.
OccupancyGrid squareGrid() {
  OccupancyGrid grid(0.05);
  SonarInverseModel model;
  model.arc_thickness_m = 0.0;
  for (int i = 0; i < 3; ++i)
    grid.integrateSonar({0.0, 0.25}, 0.0, degToRad(20.0), 0.5, true, model);
  return grid;
}

TEST(GridExport, ThresholdsSplitCellsIntoOccupiedFreeAndUnknown) {
  OccupancyGrid grid(0.1);
  // Four 1 m cones (inside -1.6: p = 0.17, free; arc +3.4: occupied), then two 0.5 m cones
  // whose arc lands on that free space (-1.6 + 2 * 0.85 = 0.1: p = 0.52, neither). Every cell
  // is checked against its probability, and each class must occur.
  SonarInverseModel model;
  for (int i = 0; i < 4; ++i)
    grid.integrateSonar({0.05, 0.05}, 0.0, degToRad(30.0), 1.0, true, model);
  for (int i = 0; i < 2; ++i)
    grid.integrateSonar({0.05, 0.05}, 0.0, degToRad(30.0), 0.5, true, model);
  const GridExportThresholds thresholds;
  const RasterMap raster = rasterFromGrid(grid, thresholds);
  ASSERT_FALSE(raster.empty());
  EXPECT_DOUBLE_EQ(raster.resolution_m, 0.1);
  int occupied = 0, free = 0, between = 0;
  for (int row = 0; row < raster.height; ++row) {
    for (int col = 0; col < raster.width; ++col) {
      const Vec2 centre = raster.cellCentre(col, row);
      const Cell cell = grid.cellAt(centre);
      const std::int8_t value = raster.at(col, row);
      if (!grid.observed(cell)) {
        EXPECT_EQ(value, RasterMap::kUnknown);
        continue;
      }
      const double p = grid.probability(cell);
      if (p > thresholds.occupied_probability) {
        EXPECT_EQ(value, RasterMap::kOccupied);
        ++occupied;
      } else if (p < thresholds.free_probability) {
        EXPECT_EQ(value, RasterMap::kFree);
        ++free;
      } else {
        EXPECT_EQ(value, RasterMap::kUnknown);
        ++between;
      }
    }
  }
  EXPECT_GT(occupied, 0);
  EXPECT_GT(free, 0);
  EXPECT_GT(between, 0);
}

TEST(GridExport, RasterCoversTheObservedCellsPlusPadding) {
  const OccupancyGrid grid = squareGrid();
  const OccupancyGrid::CellRect rect = grid.observedCellRect();
  GridExportThresholds thresholds;
  thresholds.padding_cells = 3;
  const RasterMap raster = rasterFromGrid(grid, thresholds);
  EXPECT_EQ(raster.width, rect.width() + 6);
  EXPECT_EQ(raster.height, rect.height() + 6);
  EXPECT_NEAR(raster.origin.x, (rect.col0 - 3) * 0.05, 1e-12);
  EXPECT_NEAR(raster.origin.y, (rect.row0 - 3) * 0.05, 1e-12);
  for (int col = 0; col < raster.width; ++col) {
    EXPECT_EQ(raster.at(col, 0), RasterMap::kUnknown);
    EXPECT_EQ(raster.at(col, raster.height - 1), RasterMap::kUnknown);
  }
  // Same world point, same class, in the padded and the unpadded raster.
  const RasterMap tight = rasterFromGrid(grid);
  for (int row = 0; row < tight.height; ++row)
    for (int col = 0; col < tight.width; ++col)
      ASSERT_EQ(tight.at(col, row), raster.at(col + 3, row + 3));
}

TEST(GridExport, EmptyGridGivesAnEmptyRasterAndSaveReportsIt) {
  const OccupancyGrid grid(0.02);
  const RasterMap raster = rasterFromGrid(grid);
  EXPECT_TRUE(raster.empty());
  EXPECT_DOUBLE_EQ(raster.resolution_m, 0.02);
  const auto error = saveGridAsRosMap(grid, fs::temp_directory_path() / "irgs_empty_grid.yaml");
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("no observed cells"), std::string::npos);
}

TEST(GridExport, BadThresholdsThrowOnExportAndAreReportedOnSave) {
  const OccupancyGrid grid = squareGrid();
  GridExportThresholds swapped;
  swapped.occupied_probability = 0.2;
  swapped.free_probability = 0.6;
  EXPECT_TRUE(gridExportThresholdsError(swapped).has_value());
  EXPECT_THROW(rasterFromGrid(grid, swapped), std::invalid_argument);
  GridExportThresholds nan;
  nan.free_probability = std::nan("");
  EXPECT_THROW(rasterFromGrid(grid, nan), std::invalid_argument);
  GridExportThresholds negative_pad;
  negative_pad.padding_cells = -1;
  EXPECT_THROW(rasterFromGrid(grid, negative_pad), std::invalid_argument);
  EXPECT_TRUE(saveGridAsRosMap(grid, fs::temp_directory_path() / "irgs_bad.yaml", swapped));
  EXPECT_FALSE(gridExportThresholdsError({}).has_value());
}

TEST(GridExport, SavedRosMapReadsBackToTheSameCells) {
  const OccupancyGrid grid = squareGrid();
  const fs::path dir = fs::temp_directory_path() / "irgs_grid_export_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path yaml = dir / "built.yaml";
  ASSERT_FALSE(saveGridAsRosMap(grid, yaml).has_value());
  EXPECT_TRUE(fs::exists(dir / "built.pgm"));
  const RosMapLoadResult loaded = loadRosMap(yaml);
  ASSERT_TRUE(loaded.raster.has_value());
  const RasterMap expected = rasterFromGrid(grid);
  EXPECT_EQ(loaded.raster->width, expected.width);
  EXPECT_EQ(loaded.raster->height, expected.height);
  EXPECT_NEAR(loaded.raster->resolution_m, expected.resolution_m, 1e-9);
  EXPECT_NEAR(loaded.raster->origin.x, expected.origin.x, 1e-9);
  EXPECT_NEAR(loaded.raster->origin.y, expected.origin.y, 1e-9);
  EXPECT_EQ(loaded.raster->cells, expected.cells);
  fs::remove_all(dir);
}

TEST(GridExport, AnAreaTooLargeForARasterIsRefusedNotAllocated) {
  OccupancyGrid grid(0.01);
  const SonarInverseModel model;
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(20.0), 0.5, true, model);
  grid.integrateSonar({400.0, 400.0}, 0.0, degToRad(20.0), 0.5, true, model);
  EXPECT_THROW(rasterFromGrid(grid), std::invalid_argument);
  const auto error = saveGridAsRosMap(grid, fs::temp_directory_path() / "irgs_huge.yaml");
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("too large"), std::string::npos);
}

}  // namespace
}  // namespace irgs
