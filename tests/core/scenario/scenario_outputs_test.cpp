#include "core/scenario/scenario_outputs.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/world/ros_map.hpp"

namespace irgs {
namespace {

ScenarioResult smallResult() {
  ScenarioResult r{OccupancyGrid(0.05), {}, {}};
  r.grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(30.0), 1.0, true, SonarInverseModel{});
  r.trajectory.push_back({0.0, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {}, 0});
  r.trajectory.push_back({0.1, {0.02, 0.0, 0.0}, {0.021, 0.0, 0.0}, {0.2, 0.0}, 3});
  r.metrics.duration_s = 0.1;
  r.metrics.distance_travelled_m = 0.02;
  r.metrics.final_truth = {0.02, 0.0, 0.0};
  r.metrics.final_odometry = {0.021, 0.0, 0.0};
  r.metrics.odometry_position_error_m = 0.001;
  r.metrics.explored_area_m2 = r.grid.exploredArea_m2();
  return r;
}

TEST(ScenarioOutputs, MetricsJsonCarriesPosesErrorsAndArea) {
  const ScenarioResult r = smallResult();
  const auto doc = nlohmann::json::parse(metricsJson(r.metrics, {"room.json", "thesis", 9}));
  EXPECT_EQ(doc.at("map"), "room.json");
  EXPECT_EQ(doc.at("seed"), 9);
  EXPECT_DOUBLE_EQ(doc.at("final_true_pose").at("x_m").get<double>(), 0.02);
  EXPECT_DOUBLE_EQ(doc.at("final_odometry_pose").at("x_m").get<double>(), 0.021);
  EXPECT_DOUBLE_EQ(doc.at("odometry_error").at("position_m").get<double>(), 0.001);
  EXPECT_GT(doc.at("explored_area_m2").get<double>(), 0.1);
}

TEST(ScenarioOutputs, TrajectoryCsvHasAHeaderAndOneLinePerRow) {
  const std::string csv = trajectoryCsv(smallResult().trajectory);
  std::istringstream lines(csv);
  std::string header, first, second, extra;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_FALSE(std::getline(lines, extra));
  EXPECT_EQ(header.rfind("time_s,true_x_m,", 0), 0u);
  EXPECT_EQ(second, "0.100,0.02000,0.00000,0.00000,0.02100,0.00000,0.00000,0.2000,0.0000,3");
}

TEST(ScenarioOutputs, GridPictureIsAPng) {
  const std::string png = gridPicturePng(smallResult().grid, smallResult().trajectory);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(ScenarioOutputs, WritesAllFilesAndTheGridReadsBackAsARosMap) {
  const auto dir = std::filesystem::temp_directory_path() / "irgs_scenario_outputs_test";
  std::filesystem::remove_all(dir);
  const auto written = writeScenarioOutputs(smallResult(), {"room.json", "thesis", 1}, dir);
  ASSERT_TRUE(written.error.empty()) << written.error;
  for (const char* name : {"grid.pgm", "grid.yaml", "grid.png", "metrics.json", "trajectory.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  }
  const auto ros = loadRosMap(dir / "grid.yaml");
  ASSERT_TRUE(ros.raster);
  EXPECT_NEAR(ros.raster->resolution_m, 0.05, 1e-12);
  std::filesystem::remove_all(dir);
}

TEST(ScenarioOutputs, UnwritableFolderIsReportedNotThrown) {
  const auto written = writeScenarioOutputs(smallResult(), {}, "/proc/irgs-cannot-write-here");
  EXPECT_FALSE(written.error.empty());
}

}  // namespace
}  // namespace irgs
