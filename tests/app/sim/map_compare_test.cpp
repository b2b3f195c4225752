#include "app/sim/map_compare.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/world/ros_map.hpp"

namespace irgs::app {
namespace {

namespace fs = std::filesystem;

// Three walls of a 2 m room seen by a sonar at the centre, shifted by `offset` (metres, x):
// echoes at 1 m straight ahead, to the left and to the right, many times so the arcs are firm.
OccupancyGrid roomGrid(double offset_x) {
  OccupancyGrid grid(0.01);
  const SonarInverseModel model;
  const Vec2 origin(offset_x, 0.0);
  for (int k = 0; k < 6; ++k)
    for (double heading = -1.6; heading <= 1.6; heading += 0.1)
      grid.integrateSonar(origin, heading, 0.3, 1.0, true, model);
  return grid;
}

fs::path saveGrid(const OccupancyGrid& grid, const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("irgs_map_compare_" + name);
  fs::create_directories(dir);
  const fs::path yaml = dir / "grid.yaml";
  EXPECT_FALSE(saveRosMap(grid.toRaster(), yaml).has_value());
  return yaml;
}

TEST(MapCompare, AMapAgreesFullyWithItsOwnSavedCopy) {
  const OccupancyGrid grid = roomGrid(0.0);
  const MapAgreement a = compareWithSavedMap(grid, saveGrid(grid, "same"));
  ASSERT_TRUE(a.score) << a.error;
  EXPECT_GT(a.score->built_cells, 20u);
  EXPECT_DOUBLE_EQ(a.score->precision, 1.0);
  EXPECT_DOUBLE_EQ(a.score->recall, 1.0);
  EXPECT_DOUBLE_EQ(a.score->f1, 1.0);
}

TEST(MapCompare, AShiftWithinTheToleranceStillAgreesAndOneBeyondItDoesNot) {
  const fs::path reference = saveGrid(roomGrid(0.0), "shift");
  const MapAgreement near = compareWithSavedMap(roomGrid(0.04), reference);
  ASSERT_TRUE(near.score) << near.error;
  EXPECT_GT(near.score->f1, 0.9);
  const MapAgreement far = compareWithSavedMap(roomGrid(0.40), reference);
  ASSERT_TRUE(far.score) << far.error;
  EXPECT_LT(far.score->f1, 0.6);
}

TEST(MapCompare, AMissingOrBrokenReferenceIsAnErrorNamingTheFile) {
  const OccupancyGrid grid = roomGrid(0.0);
  const fs::path missing = fs::temp_directory_path() / "irgs_map_compare_none" / "grid.yaml";
  const MapAgreement a = compareWithSavedMap(grid, missing);
  EXPECT_FALSE(a.score);
  EXPECT_NE(a.error.find(missing.string()), std::string::npos) << a.error;

  const fs::path dir = fs::temp_directory_path() / "irgs_map_compare_broken";
  fs::create_directories(dir);
  std::ofstream(dir / "grid.yaml") << "image: nothing.pgm\nresolution: -1\n";
  const MapAgreement b = compareWithSavedMap(grid, dir / "grid.yaml");
  EXPECT_FALSE(b.score);
  EXPECT_NE(b.error.find("grid.yaml"), std::string::npos) << b.error;
}

TEST(MapCompare, ScoringGridMarksTheCellsHoldingOccupiedRasterCells) {
  RasterMap raster;
  raster.width = 10;
  raster.height = 10;
  raster.resolution_m = 0.01;
  raster.origin = {0.2, 0.3, 0.0};
  raster.cells.assign(100, RasterMap::kFree);
  raster.at(0, 0) = RasterMap::kOccupied;  // (0.205, 0.305): scoring cell (4, 6) on 5 cm
  raster.at(9, 9) = RasterMap::kUnknown;
  const PlanningGrid g = occupiedScoringGrid(raster, 0.05, 65, 0.1);
  EXPECT_EQ(g.blockedCount(), 1u);
  const auto c = g.worldToCell({0.205, 0.305});
  ASSERT_TRUE(c);
  EXPECT_FALSE(g.isFree(*c));
  EXPECT_NEAR(g.origin.x(), 0.1, 1e-12);  // on the 5 cm lattice, 0.1 m beyond the raster
  EXPECT_THROW(occupiedScoringGrid(raster, 0.0), std::invalid_argument);
  EXPECT_THROW(occupiedScoringGrid(raster, 0.05, 65, -1.0), std::invalid_argument);
  EXPECT_THROW(occupiedScoringGrid(RasterMap{}, 0.05), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::app
