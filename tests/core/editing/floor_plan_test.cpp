// The floor-plan image: placement, two-point calibration, the undoable edit and the map format.
#include "core/editing/floor_plan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "core/editing/map_edit.hpp"
#include "core/world/map_file.hpp"

namespace irgs::editing {
namespace {

FloorPlan plan() {
  FloorPlan p;
  p.source = "plan.png";
  p.metres_per_pixel = 0.05;
  p.origin = {-1.0, 4.0};
  return p;
}

TEST(FloorPlan, PixelsRunRightAndDownFromTheTopLeftCorner) {
  const FloorPlan p = plan();
  EXPECT_TRUE(floorPlanToWorld(p, {0, 0}).isApprox(Vec2(-1.0, 4.0)));
  EXPECT_TRUE(floorPlanToWorld(p, {100, 0}).isApprox(Vec2(4.0, 4.0)));
  EXPECT_TRUE(floorPlanToWorld(p, {0, 80}).isApprox(Vec2(-1.0, 0.0)));
  FloorPlan turned = p;
  turned.rotation_rad = std::numbers::pi / 2.0;
  EXPECT_TRUE(floorPlanToWorld(turned, {100, 0}).isApprox(Vec2(-1.0, 9.0)));
  EXPECT_TRUE(worldToFloorPlan(turned, floorPlanToWorld(turned, {37, 12})).isApprox(Vec2(37, 12)));
}

TEST(FloorPlan, TwoPointsWithTheirWorldPositionsFixScaleRotationAndOrigin) {
  // A drawing at 1 px = 2 cm, turned by 30 degrees, whose pixel (0, 0) is at (3, -2).
  FloorPlan truth = plan();
  truth.metres_per_pixel = 0.02;
  truth.rotation_rad = std::numbers::pi / 6.0;
  truth.origin = {3.0, -2.0};
  const Vec2 a(120, 340), b(810, 95);  // two door corners clicked on the image
  const auto calibrated =
      calibrateFloorPlan(plan(), a, b, floorPlanToWorld(truth, a), floorPlanToWorld(truth, b));
  ASSERT_TRUE(calibrated);
  EXPECT_NEAR(calibrated->metres_per_pixel, 0.02, 1e-12);
  EXPECT_NEAR(calibrated->rotation_rad, std::numbers::pi / 6.0, 1e-12);
  EXPECT_TRUE(calibrated->origin.isApprox(Vec2(3.0, -2.0), 1e-12));
  EXPECT_EQ(calibrated->source, "plan.png");
  EXPECT_FALSE(calibrateFloorPlan(plan(), a, a, Vec2(0, 0), Vec2(1, 0)));
  EXPECT_FALSE(calibrateFloorPlan(plan(), a, b, Vec2(1, 1), Vec2(1, 1)));
}

TEST(FloorPlan, ADistanceRescalesAboutTheFirstPoint) {
  const FloorPlan p = plan();
  const Vec2 a(20, 20), b(20 + 300, 20 + 400);  // 500 px apart
  const Vec2 a_world = floorPlanToWorld(p, a);
  const auto calibrated = calibrateFloorPlanByDistance(p, a, b, 10.0);
  ASSERT_TRUE(calibrated);
  EXPECT_NEAR(calibrated->metres_per_pixel, 0.02, 1e-12);
  EXPECT_NEAR(calibrated->rotation_rad, 0.0, 1e-12);
  EXPECT_TRUE(floorPlanToWorld(*calibrated, a).isApprox(a_world, 1e-12));
  EXPECT_NEAR((floorPlanToWorld(*calibrated, b) - a_world).norm(), 10.0, 1e-9);
  EXPECT_FALSE(calibrateFloorPlanByDistance(p, a, b, 0.0));
  EXPECT_FALSE(calibrateFloorPlanByDistance(p, a, a, 2.0));
}

TEST(FloorPlan, SetFloorPlanIsOneUndoableStepAndBadValuesAreRefused) {
  WorldMap map;
  const std::string before = serializeMap(map);
  const Edit add = setFloorPlan(map, plan());
  applyEdit(map, add);
  ASSERT_TRUE(map.floor_plan);
  FloorPlan scaled = *map.floor_plan;
  scaled.metres_per_pixel = 0.01;
  const Edit calibrate = setFloorPlan(map, scaled, "Calibrate floor plan");
  applyEdit(map, calibrate);
  EXPECT_EQ(map.floor_plan->metres_per_pixel, 0.01);
  revertEdit(map, calibrate);
  EXPECT_EQ(map.floor_plan->metres_per_pixel, 0.05);
  revertEdit(map, add);
  EXPECT_EQ(serializeMap(map), before);
  FloorPlan bad = plan();
  bad.metres_per_pixel = 0.0;
  EXPECT_THROW(setFloorPlan(map, bad), std::invalid_argument);
  bad = plan();
  bad.opacity = 1.5;
  EXPECT_THROW(setFloorPlan(map, bad), std::invalid_argument);
  bad = plan();
  bad.source.clear();
  EXPECT_THROW(setFloorPlan(map, bad), std::invalid_argument);
}

TEST(FloorPlanFormat, TheImageIsReferencedRelativeToTheMapFileAndRoundTrips) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "irgs_floor_plan_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "plans");
  fs::create_directories(dir / "maps");
  std::ofstream(dir / "plans" / "floor.png") << "not decoded by core";
  WorldMap map;
  Wall w;
  w.points = {{0, 0}, {1, 0}};
  map.walls.push_back(w);
  FloorPlan p = plan();
  p.source = "floor.png";
  p.resolved_path = (dir / "plans" / "floor.png").string();
  p.opacity = 0.4;
  map.floor_plan = p;
  ASSERT_FALSE(saveMapFile(map, dir / "maps" / "m.json"));
  const MapLoadResult loaded = loadMapFile(dir / "maps" / "m.json");
  ASSERT_TRUE(loaded.map);
  ASSERT_TRUE(loaded.map->floor_plan);
  EXPECT_EQ(loaded.map->floor_plan->source, "../plans/floor.png");
  EXPECT_EQ(fs::path(loaded.map->floor_plan->resolved_path),
            fs::absolute(dir / "plans" / "floor.png").lexically_normal());
  EXPECT_EQ(loaded.map->floor_plan->opacity, 0.4);
  EXPECT_TRUE(loaded.map->floor_plan->origin.isApprox(p.origin));
  EXPECT_TRUE(loaded.diagnostics.empty());
  // A missing image loads with a warning (the map is still usable); a bad scale is an error.
  std::string text = serializeMap(*loaded.map);
  const MapLoadResult missing = parseMapJson(text, "x.json", dir / "elsewhere");
  ASSERT_TRUE(missing.map);
  ASSERT_EQ(missing.diagnostics.size(), 1u);
  EXPECT_NE(missing.diagnostics[0].toString().find("/floor_plan/source"), std::string::npos);
  text.replace(text.find("\"metres_per_pixel\": 0.05"), 24, "\"metres_per_pixel\": -1");
  EXPECT_FALSE(parseMapJson(text, "x.json", dir / "maps").map);
  // Maps without a floor plan do not mention it.
  map.floor_plan.reset();
  EXPECT_EQ(serializeMap(map).find("floor_plan"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace irgs::editing
