#include "core/scenario/scenario_runner.hpp"

#include <gtest/gtest.h>

#include "core/robot/robot_profile_file.hpp"

namespace irgs {
namespace {

RobotProfile thesisRobot() {
  auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  EXPECT_TRUE(loaded.profile) << (loaded.diagnostics.empty() ? ""
                                                             : loaded.diagnostics[0].toString());
  return loaded.profile.value_or(RobotProfile{});
}

// A closed square room of the given half size, centred on the origin.
WorldMap squareRoom(double half_m) {
  WorldMap map;
  map.name = "square";
  map.walls.push_back({"room",
                       {{-half_m, -half_m}, {half_m, -half_m}, {half_m, half_m}, {-half_m, half_m}},
                       true,
                       {}});
  return map;
}

DriveScript script(std::vector<DriveScriptStep> steps) {
  return DriveScript(std::move(steps));
}

ScenarioSpec straightDrive(double seconds) {
  ScenarioSpec spec;
  spec.map = squareRoom(3.0);
  spec.profile = thesisRobot();
  spec.script = script({{0.0, {0.2, 0.0}, 0}, {seconds, {0.0, 0.0}, 0}});
  spec.duration_s = seconds + 1.0;
  return spec;
}

TEST(ScenarioRunner, GoldenStraightDriveWithoutErrorsEndsOneMetreAhead) {
  ScenarioSpec spec = straightDrive(5.0);
  spec.sim = idealSimConfig(spec.sim);
  const ScenarioResult r = runScenario(spec);
  // 0.2 m/s for 5 s, less what the acceleration limit takes at the start and gives back at the
  // stop: the robot ends within a few centimetres of x = 1 m, on the line, heading unchanged.
  EXPECT_NEAR(r.metrics.final_truth.x, 1.0, 0.05);
  EXPECT_NEAR(r.metrics.final_truth.y, 0.0, 1e-9);
  EXPECT_NEAR(r.metrics.final_truth.theta, 0.0, 1e-9);
  EXPECT_NEAR(r.metrics.distance_travelled_m, r.metrics.final_truth.x, 1e-9);
  // Ideal odometry only quantises encoder ticks.
  EXPECT_LT(r.metrics.odometry_position_error_m, 0.002);
  EXPECT_EQ(r.metrics.steps, 600u);
  EXPECT_DOUBLE_EQ(r.metrics.duration_s, 6.0);
}

TEST(ScenarioRunner, RecordsATrajectoryRowPerPeriodFromTimeZero) {
  const ScenarioResult r = runScenario(straightDrive(2.0));
  ASSERT_EQ(r.trajectory.size(), 31u);  // t = 0, 0.1, ..., 3.0
  EXPECT_DOUBLE_EQ(r.trajectory.front().time_s, 0.0);
  EXPECT_NEAR(r.trajectory.back().time_s, 3.0, 1e-9);
  EXPECT_NEAR(r.trajectory[5].command.linear_mps, 0.2, 1e-12);
}

TEST(ScenarioRunner, SonarFillsTheGridWhileStandingStill) {
  ScenarioSpec spec;
  spec.map = squareRoom(1.5);
  spec.profile = thesisRobot();
  spec.duration_s = 2.0;
  const ScenarioResult r = runScenario(spec);
  EXPECT_GT(r.metrics.sonar_readings, 0u);
  EXPECT_GT(r.metrics.sonar_echoes, 0u);
  EXPECT_GT(r.metrics.explored_area_m2, 1.0);
  EXPECT_DOUBLE_EQ(r.metrics.distance_travelled_m, 0.0);
}

TEST(ScenarioRunner, SameSeedGivesIdenticalResultsAndAnotherSeedDiffers) {
  ScenarioSpec spec = straightDrive(4.0);
  spec.sim.seed = 3;
  const ScenarioResult a = runScenario(spec);
  const ScenarioResult b = runScenario(spec);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    EXPECT_EQ(a.trajectory[i].truth, b.trajectory[i].truth);
    EXPECT_EQ(a.trajectory[i].odometry, b.trajectory[i].odometry);
  }
  EXPECT_EQ(a.grid.toRaster().cells, b.grid.toRaster().cells);

  spec.sim.seed = 4;
  const ScenarioResult c = runScenario(spec);
  EXPECT_NE(a.grid.toRaster().cells, c.grid.toRaster().cells);
}

TEST(ScenarioRunner, DrivingIntoAWallCountsABumperPressAndStopsThere) {
  ScenarioSpec spec;
  spec.map = squareRoom(1.0);
  spec.profile = thesisRobot();
  spec.sim = idealSimConfig(spec.sim);
  spec.script = script({{0.0, {0.3, 0.0}, 0}});
  spec.duration_s = 8.0;
  const ScenarioResult r = runScenario(spec);
  EXPECT_GE(r.metrics.bumper_events, 1u);
  EXPECT_LT(r.metrics.final_truth.x, 1.0 - 0.1);  // the body stays out of the wall
  EXPECT_NE(r.trajectory.back().bumpers, 0u);
}

TEST(ScenarioRunner, StartOverridesTheMapStartPose) {
  ScenarioSpec spec;
  spec.map = squareRoom(3.0);
  spec.map.start = {1.0, 1.0, 0.0};
  spec.profile = thesisRobot();
  spec.start = Pose2{-1.0, 0.5, kPi / 2.0};
  spec.duration_s = 0.5;
  const ScenarioResult r = runScenario(spec);
  EXPECT_EQ(r.trajectory.front().truth, *spec.start);
  EXPECT_EQ(r.metrics.final_odometry, *spec.start);
}

}  // namespace
}  // namespace irgs
