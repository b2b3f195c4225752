#include "core/mapping/hybrid_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/estimation/ekf_localizer.hpp"
#include "core/estimation/stereo_echo_sim.hpp"
#include "core/estimation/stereo_measurement_model.hpp"
#include "core/sim/diff_drive.hpp"
#include "core/sim/random.hpp"
#include "core/world/map_file.hpp"
#include "simulated_survey.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;

const HybridMap& builtLoop() {
  static const HybridMap map =
      HybridMap::fromGrid(test::surveyGrid(test::loadBundledMap("thesis_sim1_loop")));
  return map;
}

TEST(HybridMap, ExportsLinesAsWallsPointsAsFeaturesAndTheGridAsRaster) {
  const HybridMap& map = builtLoop();
  ASSERT_GT(map.features.lines.size(), 5u);
  ASSERT_GT(map.features.points.size(), 2u);
  HybridMapExportOptions options;
  options.name = "loop (built)";
  options.start = {3.0, 2.0, 0.0};
  const WorldMap world = map.toWorldMap(options);
  EXPECT_EQ(world.name, "loop (built)");
  EXPECT_EQ(world.start, options.start);
  ASSERT_EQ(world.walls.size(), map.features.lines.size());
  for (std::size_t k = 0; k < world.walls.size(); ++k) {
    ASSERT_EQ(world.walls[k].points.size(), 2u);
    EXPECT_EQ(world.walls[k].points[0], map.features.lines[k].segment.a);
    EXPECT_EQ(world.walls[k].points[1], map.features.lines[k].segment.b);
  }
  ASSERT_EQ(world.features.size(), map.features.points.size());
  for (std::size_t k = 0; k < world.features.size(); ++k) {
    EXPECT_EQ(world.features[k].kind, map.features.points[k].kind);
    EXPECT_EQ(world.features[k].position, map.features.points[k].position);
    EXPECT_EQ(world.features[k].id[0],
              world.features[k].kind == PointFeatureKind::kCorner ? 'C' : 'E');
  }
  ASSERT_TRUE(world.raster.has_value());
  EXPECT_EQ(world.raster->raster.cells, rasterFromGrid(map.grid).cells);
  // The EKF's map: both faces of every wall, every point.
  const LocalizationMap loc = buildLocalizationMap(world);
  EXPECT_EQ(loc.walls.size(), 2 * world.walls.size());
  EXPECT_EQ(loc.points.size(), world.features.size());
}

TEST(HybridMap, SavedMapLoadsBackWithItsRaster) {
  const HybridMap& map = builtLoop();
  const fs::path dir = fs::temp_directory_path() / "irgs_hybrid_map_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_FALSE(saveHybridMap(map, dir / "built.json").has_value());
  EXPECT_TRUE(fs::exists(dir / "built_grid.yaml"));
  EXPECT_TRUE(fs::exists(dir / "built_grid.pgm"));
  const MapLoadResult loaded = loadMapFile(dir / "built.json");
  ASSERT_TRUE(loaded.map.has_value())
      << (loaded.diagnostics.empty() ? std::string() : loaded.diagnostics.front().message);
  const WorldMap expected = map.toWorldMap();
  ASSERT_EQ(loaded.map->walls.size(), expected.walls.size());
  for (std::size_t k = 0; k < expected.walls.size(); ++k)
    for (std::size_t i = 0; i < 2; ++i)
      EXPECT_LT((loaded.map->walls[k].points[i] - expected.walls[k].points[i]).norm(), 1e-6);
  ASSERT_EQ(loaded.map->features.size(), expected.features.size());
  ASSERT_TRUE(loaded.map->raster.has_value());
  EXPECT_EQ(loaded.map->raster->source, "built_grid.yaml");
  EXPECT_EQ(loaded.map->raster->raster.cells, expected.raster->raster.cells);
  EXPECT_EQ(loaded.map->raster->raster.width, expected.raster->raster.width);
  fs::remove_all(dir);
}

TEST(HybridMap, SavingAnEmptyMapOrWithBadThresholdsReportsAnError) {
  const HybridMap empty = HybridMap::fromGrid(OccupancyGrid(0.01));
  EXPECT_TRUE(empty.features.lines.empty());
  EXPECT_FALSE(empty.toWorldMap().raster.has_value());
  const fs::path path = fs::temp_directory_path() / "irgs_hybrid_empty.json";
  EXPECT_TRUE(saveHybridMap(empty, path).has_value());
  HybridMapExportOptions bad;
  bad.thresholds.free_probability = 0.9;
  EXPECT_TRUE(saveHybridMap(builtLoop(), path, bad).has_value());
  EXPECT_THROW(builtLoop().toWorldMap(bad), std::invalid_argument);
}

TEST(HybridMap, CellTagsCombineTheWeightsWithTheFeatures) {
  const HybridMap& map = builtLoop();
  const ExtractedLine& line = map.features.lines.front();
  const Vec2 mid = 0.5 * (line.segment.a + line.segment.b);
  EXPECT_EQ(map.tagAt(map.grid.cellAt(mid)), CellTag::kPlane);
  const ExtractedPoint& point = map.features.points.front();
  const CellTag point_tag =
      point.kind == PointFeatureKind::kCorner ? CellTag::kCorner : CellTag::kEdge;
  EXPECT_EQ(map.tagAt(map.grid.cellAt(point.position)), point_tag);
  EXPECT_EQ(map.tagAt(map.grid.cellAt({3.0, 1.0})), CellTag::kFree);  // middle of the room
  EXPECT_EQ(map.tagAt(map.grid.cellAt({-3.0, -3.0})), CellTag::kUnknown);
  // The bulk form agrees with the single-cell form.
  const Cell c = map.grid.cellAt(mid);
  const OccupancyGrid::CellRect rect{c.col - 5, c.row - 5, c.col + 5, c.row + 5};
  std::vector<CellTag> tags;
  map.tags(rect, tags);
  ASSERT_EQ(tags.size(), 121u);
  for (int r = rect.row0; r <= rect.row1; ++r)
    for (int col = rect.col0; col <= rect.col1; ++col)
      ASSERT_EQ(tags[static_cast<std::size_t>((r - rect.row0) * 11 + (col - rect.col0))],
                map.tagAt({col, r}));
  EXPECT_STREQ(toString(CellTag::kPlane), "plane");
}

// Paper-000 EKF localisation on the map the robot built: the echoes come from the true world,
// the filter matches them against the exported (built) walls and corners.
TEST(HybridMap, EkfLocalisesOnTheBuiltMap) {
  const WorldMap truth_map = test::loadBundledMap("thesis_sim1_loop");
  const LocalizationMap built = buildLocalizationMap(builtLoop().toWorldMap());
  StereoEchoNoise noise;
  noise.dropout_probability = 0.05;
  const StereoEchoSimulator sonar(truth_map, {}, noise);
  SimRandom motion_rng = SimRandom::stream(7, 1);
  SimRandom sonar_rng = SimRandom::stream(7, 2);

  constexpr double kDt = 0.01, kWheelbase = 0.24, kSpeed = 0.3;
  const Pose2 start{1.0, 1.0, 0.0};
  const std::vector<Vec2> waypoints = {{5.0, 1.0}, {5.0, 3.0}, {1.0, 3.0}};
  const SensorMount right{0.0, -0.1, -kPi / 2}, left{0.0, 0.1, kPi / 2}, front{0.15, 0.0, 0.0};
  LocCov p0 = LocCov::Zero();
  p0.diagonal() << 0.01 * 0.01, 0.01 * 0.01, degToRad(1.0) * degToRad(1.0);
  // A Mahalanobis gate (49) (3 sigma per scalar): the built map has stray lines that an
  // ungated filter would accept as matches.
  EkfLocalizerConfig config;
  config.gate = 9.0;
  EkfLocalizer ekf(toLocState(start), p0, config);
  DiffDriveNoise process;
  process.wheel_variance_per_m = 2e-4;

  Pose2 truth = start, dead_reckoning = start;
  int readings = 0, updates = 0;
  double max_error = 0.0;
  std::size_t target = 0;
  for (long step = 0; target < waypoints.size() && step < 200'000; ++step) {
    const Vec2 to_goal = waypoints[target] - truth.position();
    if (to_goal.norm() < 0.03) {
      ++target;
      continue;
    }
    const double heading_error = wrapAngle(std::atan2(to_goal.y(), to_goal.x()) - truth.theta);
    const double omega = std::clamp(2.0 * heading_error, -0.6, 0.6);
    const double v = std::abs(heading_error) > 0.1 ? 0.0 : std::min(kSpeed, to_goal.norm());
    const WheelSpeeds ws = wheelSpeeds(v, omega, kWheelbase);
    const double left_true = ws.left_mps * kDt * (1.0 + 0.002 * motion_rng.gaussian());
    const double right_true = ws.right_mps * kDt * (1.0 + 0.002 * motion_rng.gaussian());
    truth =
        integrateArc(truth, 0.5 * (left_true + right_true), (right_true - left_true) / kWheelbase);
    // The encoders believe a nominal wheel 1 % and 0.4 % smaller than the true ones.
    const double left_odo = left_true / 1.01, right_odo = right_true / 1.004;
    dead_reckoning = integrateArc(dead_reckoning, 0.5 * (left_odo + right_odo),
                                  (right_odo - left_odo) / kWheelbase);
    ASSERT_EQ(ekf.predictDiffDrive(left_odo, right_odo, kWheelbase, process),
              PredictStatus::kApplied);
    if (step % 4 != 0)
      continue;
    for (const SensorMount& mount : {right, left, front}) {
      const SimulatedEcho echo = sonar.echo(sensorWorldPose(toLocState(truth), mount), sonar_rng);
      if (echo.status != EchoStatus::kEcho)
        continue;
      ++readings;
      const LocalizationUpdate u = ekf.update(echo.paths, {mount, 0.2}, built);
      if (u.status == UpdateStatus::kUpdated)
        ++updates;
    }
    max_error = std::max(max_error, (ekf.pose().position() - truth.position()).norm());
  }
  ASSERT_EQ(target, waypoints.size()) << "the run did not finish";
  const double final_error = (ekf.pose().position() - truth.position()).norm();
  const double dr_error = (dead_reckoning.position() - truth.position()).norm();
  RecordProperty("final_ekf_error_m", std::to_string(final_error));
  RecordProperty("final_dr_error_m", std::to_string(dr_error));
  EXPECT_GT(updates, readings / 2);
  EXPECT_LT(final_error, 0.06);
  EXPECT_LT(max_error, 0.1);
  EXPECT_LT(std::abs(wrapAngle(ekf.pose().theta - truth.theta)), degToRad(3.0));
  EXPECT_GT(dr_error, 2.0 * final_error);
}

}  // namespace
}  // namespace irgs
