// EstimatorRunner: the per-sample driver of the localization estimators behind the GUI's
// localization panel and irgs-sim --localize, fed by the real Simulator.

#include "core/estimation/estimator_runner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulator.hpp"
#include "core/world/map_file.hpp"

namespace irgs {
namespace {

RobotProfile mouseRobot() {
  auto loaded = loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) +
                                     "/resources/robots/mouse_type20_004.json");
  EXPECT_TRUE(loaded.profile.has_value());
  return *loaded.profile;
}

RobotProfile casterRobot() {
  auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/caster3_000.json");
  EXPECT_TRUE(loaded.profile.has_value());
  return *loaded.profile;
}

RobotProfile thesisRobot() {
  auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  EXPECT_TRUE(loaded.profile.has_value());
  return *loaded.profile;
}

WorldMap corridor() {
  const MapLoadResult loaded =
      loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/corridor_000_table1.json");
  EXPECT_TRUE(loaded.map.has_value());
  return *loaded.map;
}

// Drives the simulator through `waypoints` on its true pose (the estimator only observes) and
// feeds every sample to `runner`. Returns the number of samples.
long drive(Simulator& sim, EstimatorRunner& runner, const std::vector<Vec2>& waypoints,
           double speed_mps = 0.3, long max_steps = 200'000) {
  TelemetrySample sample;
  std::size_t target = 0;
  long steps = 0;
  for (; target < waypoints.size() && steps < max_steps; ++steps) {
    const Pose2 truth = sim.truePose();
    const Vec2 to_goal = waypoints[target] - truth.position();
    if (to_goal.norm() < 0.05) {
      ++target;
      continue;
    }
    const double heading_error = wrapAngle(std::atan2(to_goal.y(), to_goal.x()) - truth.theta);
    const double omega = std::clamp(2.0 * heading_error, -0.8, 0.8);
    const double v = std::abs(heading_error) > 0.15 ? 0.0 : std::min(speed_mps, to_goal.norm());
    sim.setCommand({v, omega});
    sim.step(sample);
    runner.feed(sample);
  }
  EXPECT_EQ(target, waypoints.size()) << "the route did not finish";
  return steps;
}

SimConfig drifty(std::uint64_t seed) {
  SimConfig c;
  c.seed = seed;
  c.odometry.left_scale = 1.01;
  c.odometry.right_scale = 1.004;
  c.odometry.slip_stddev = 0.002;
  return c;
}

TEST(EstimatorRunner, NamesRoundTripAndUnknownNamesAreRejected) {
  for (EstimatorKind k : kAllEstimatorKinds)
    EXPECT_EQ(parseEstimatorKind(toString(k)), k);
  EXPECT_EQ(parseEstimatorKind("mouse"), EstimatorKind::kMouseOdometry);
  EXPECT_FALSE(parseEstimatorKind("EKF").has_value());
  EXPECT_FALSE(parseEstimatorKind("").has_value());
}

TEST(EstimatorRunner, InvalidConfigOrPoseThrows) {
  const WorldMap map = corridor();
  const RobotProfile robot = thesisRobot();
  EstimatorRunnerConfig bad;
  bad.stereo_period_s = 0.0;
  EXPECT_THROW(EstimatorRunner(map, robot, map.start, bad), std::invalid_argument);
  bad = {};
  bad.initial_position_stddev_m = std::nan("");
  EXPECT_THROW(EstimatorRunner(map, robot, map.start, bad), std::invalid_argument);
  bad = {};
  bad.sensors.clear();
  EXPECT_THROW(EstimatorRunner(map, robot, map.start, bad), std::invalid_argument);
  EXPECT_THROW(EstimatorRunner(map, robot, {0.0, std::nan(""), 0.0}, {}), std::invalid_argument);
  RobotProfile no_wheels = robot;
  no_wheels.drive.wheelbase_m = 0.0;
  EXPECT_THROW(EstimatorRunner(map, no_wheels, map.start, {}), std::invalid_argument);
}

TEST(EstimatorRunner, TickIncrementsDriveDeadReckoningAndTheFirstSampleIsABaseline) {
  const WorldMap map;  // empty: no echoes
  const RobotProfile robot = thesisRobot();
  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kDeadReckoning;
  EstimatorRunner runner(map, robot, {1.0, 2.0, 0.0}, config);
  TelemetrySample s;
  s.left_ticks = s.right_ticks = 5000;  // whatever the robot counted before
  s.true_pose = Pose2{1.0, 2.0, 0.0};
  EXPECT_FALSE(runner.feed(s).predicted);
  EXPECT_DOUBLE_EQ(runner.lastStep().estimate.x, 1.0);
  // 0.1 m straight on both wheels.
  const auto ticks = static_cast<std::int64_t>(std::llround(0.1 / robot.drive.metresPerTick()));
  s.time_s = 0.5;
  s.left_ticks += ticks;
  s.right_ticks += ticks;
  s.true_pose = Pose2{1.1, 2.0, 0.0};
  const EstimatorStep& step = runner.feed(s);
  EXPECT_TRUE(step.predicted);
  EXPECT_NEAR(step.estimate.x, 1.1, 1e-3);
  EXPECT_NEAR(step.dead_reckoning.x, 1.1, 1e-3);
  EXPECT_NEAR(step.estimate.y, 2.0, 1e-12);
  // The covariance grew along the motion.
  EXPECT_GT(step.covariance(kLocX, kLocX), 0.05 * 0.05);
  ASSERT_TRUE(step.error.has_value());
  ASSERT_TRUE(step.nees.has_value());
  EXPECT_LT(*step.nees, 1.0);
  EXPECT_EQ(runner.metrics().steps, 2);
}

TEST(EstimatorRunner, AReplacedRobotReBaselinesInsteadOfJumping) {
  const WorldMap map;
  const RobotProfile robot = thesisRobot();
  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kDeadReckoning;
  EstimatorRunner runner(map, robot, {}, config);
  TelemetrySample s;
  runner.feed(s);
  s.time_s = 0.01;
  s.left_ticks = 10'000'000;  // hundreds of metres in one step
  const EstimatorStep& jump = runner.feed(s);
  EXPECT_FALSE(jump.predicted);
  EXPECT_NE(jump.note.find("encoder jump"), std::string::npos);
  EXPECT_DOUBLE_EQ(jump.estimate.x, 0.0);
  s.time_s = 0.005;
  EXPECT_NE(runner.feed(s).note.find("backwards"), std::string::npos);
  s.time_s = std::nan("");
  EXPECT_NE(runner.feed(s).note.find("non-finite"), std::string::npos);
  EXPECT_TRUE(std::isfinite(runner.lastStep().estimate.x));
}

TEST(EstimatorRunner, OnTheBundledCorridorTheEkfStaysBoundedWhileDeadReckoningGrows) {
  const WorldMap map = corridor();
  const RobotProfile robot = thesisRobot();
  Simulator sim(map, robot, drifty(3));
  EstimatorRunner runner(map, robot, map.start, {});
  // One lap clockwise around the central block (about 70 m).
  drive(sim, runner, {{15.9, 0.775}, {15.9, -14.55}, {-1.0, -14.55}, {-1.0, 0.775}, {2.0, 0.775}});
  const EstimatorMetrics& m = runner.metrics();
  EXPECT_GT(m.distance_m, 60.0);
  EXPECT_LT(m.max_position_error_m, 0.25);
  EXPECT_LT(m.final_position_error_m, 0.1);
  EXPECT_GT(m.dr_final_position_error_m, 1.0);
  EXPECT_GT(m.dr_final_position_error_m, 10.0 * m.final_position_error_m);
  EXPECT_GT(m.acceptedFraction(), 0.5);
  EXPECT_GE(m.nees_within_95, 0.9);
  RecordProperty("ekf_max_error_m", std::to_string(m.max_position_error_m));
  RecordProperty("dr_final_error_m", std::to_string(m.dr_final_position_error_m));
}

TEST(EstimatorRunner, StereoReadingsReportTheMatchedFeatureInnovationAndGate) {
  const WorldMap map = corridor();
  const RobotProfile robot = thesisRobot();
  Simulator sim(map, robot, drifty(5));
  EstimatorRunnerConfig config;
  config.ekf.gate = 9.0;
  EstimatorRunner runner(map, robot, map.start, config);
  TelemetrySample sample;
  int accepted = 0, with_readings = 0;
  sim.setCommand({0.3, 0.0});
  for (int i = 0; i < 400; ++i) {
    sim.step(sample);
    const EstimatorStep& step = runner.feed(sample);
    if (!step.readings.empty())
      ++with_readings;
    for (const StereoReadingRecord& r : step.readings) {
      ASSERT_LT(r.sensor, config.sensors.size());
      if (!r.accepted)
        continue;
      ++accepted;
      EXPECT_NE(r.update.match, MatchKind::kNone);
      EXPECT_FALSE(r.update.feature_id.empty());
      EXPECT_TRUE(r.update.distance.attempted);
      EXPECT_GT(r.update.distance.s, 0.0);
      EXPECT_LE(r.update.distance.nis, config.ekf.gate);
    }
  }
  // One firing per 40 ms period on 10 ms samples.
  EXPECT_NEAR(with_readings, 100, 1);
  EXPECT_GT(accepted, 100);
}

TEST(EstimatorRunner, TheSameSeedGivesTheSameRunAndResetRestarts) {
  const WorldMap map = corridor();
  const RobotProfile robot = thesisRobot();
  auto run = [&](EstimatorRunner& runner) {
    Simulator sim(map, robot, drifty(7));
    TelemetrySample sample;
    sim.setCommand({0.3, 0.1});
    for (int i = 0; i < 300; ++i) {
      sim.step(sample);
      runner.feed(sample);
    }
    return runner.lastStep().estimate;
  };
  EstimatorRunner a(map, robot, map.start, {});
  EstimatorRunner b(map, robot, map.start, {});
  const Pose2 pa = run(a);
  const Pose2 pb = run(b);
  EXPECT_EQ(pa.x, pb.x);
  EXPECT_EQ(pa.y, pb.y);
  EXPECT_EQ(pa.theta, pb.theta);
  a.reset(map.start);
  EXPECT_EQ(a.metrics().steps, 0);
  const Pose2 again = run(a);
  EXPECT_EQ(again.x, pa.x);
  EXPECT_EQ(again.theta, pa.theta);
}

TEST(EstimatorRunner, TheEncoderGyroFilterKeepsTheHeadingBetterThanEncoders) {
  const WorldMap map;
  RobotProfile robot = thesisRobot();
  SimConfig sim_config = drifty(11);
  sim_config.odometry.wheelbase_scale = 1.02;  // every turn costs the encoders 2 % of heading
  sim_config.gyro = autogyroErrorModel();
  sim_config.gyro.enabled = true;
  Simulator sim(map, robot, sim_config);
  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kEncoderGyro;
  config.gyro_calibration = idealGyroCalibration(sim_config.gyro);
  config.encoder_gyro.wheelbase_stddev_m = 0.02 * robot.drive.wheelbase_m;
  config.encoder_gyro.encoder_scale_stddev = 0.01;
  config.encoder_gyro.gyro_bias_stddev_radps = degToRad(0.01);
  EstimatorRunner runner(map, robot, {}, config);
  // A 3 m square, twice.
  std::vector<Vec2> square = {{3, 0}, {3, 3}, {0, 3}, {0, 0}};
  square.insert(square.end(), square.begin(), square.end());
  drive(sim, runner, square, 0.3);
  const EstimatorMetrics& m = runner.metrics();
  EXPECT_GT(m.readings, 1000);
  EXPECT_GT(m.acceptedFraction(), 0.9);
  ASSERT_TRUE(runner.lastStep().encoder_gyro.has_value());
  EXPECT_LT(m.final_heading_error_rad, 0.5 * m.dr_final_heading_error_rad);
  EXPECT_LT(m.final_position_error_m, m.dr_final_position_error_m);
}

}  // namespace
}  // namespace irgs

namespace irgs {
namespace {

TEST(EstimatorRunner, MouseOdometryNeedsAProfileWithFloorSensors) {
  const WorldMap map;
  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kMouseOdometry;
  try {
    EstimatorRunner runner(map, thesisRobot(), map.start, config);
    FAIL() << "the thesis robot has no floor sensors";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/drive/mouse_sensors"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(EstimatorRunner(map, mouseRobot(), map.start, config));
}

// The Type (2,0) robot of 004 in the Simulator with its two floor sensors: the mouse odometry
// does not see the wheels' radius and wheelbase errors, so on the same run it ends far closer to
// the truth than the encoder dead reckoning, and its readings are all counted.
TEST(EstimatorRunner, MouseOdometryInTheSimulatorBeatsTheEncodersOnTheSameRun) {
  WorldMap map;  // an open floor: the mice need no walls
  map.start = {0.0, 0.0, 0.0};
  SimConfig sim_config = drifty(3);
  sim_config.mouse_noise.scale_error = 0.005;  // [A] as in docs/localization.md
  sim_config.mouse_noise.relative_stddev = 0.01;
  Simulator sim(map, mouseRobot(), sim_config);
  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kMouseOdometry;
  EstimatorRunner runner(map, mouseRobot(), map.start, config);
  const std::vector<Vec2> square = {{2, 0}, {2, 2}, {0, 2}, {0, 0}, {2, 0}, {2, 2}, {0, 2}, {0, 0}};
  const long steps = drive(sim, runner, square);
  const EstimatorMetrics& m = runner.metrics();
  EXPECT_GT(m.distance_m, 15.0);
  // One floor-sensor reading per simulator step but the baseline (drive() also counts the
  // waypoint switches, one per waypoint, as steps).
  EXPECT_EQ(m.readings, steps - static_cast<long>(square.size()) - 1);
  EXPECT_GT(m.accepted, m.readings * 99 / 100);
  std::printf("mouse RMS %.3f m final %.3f m; encoders RMS %.3f m final %.3f m over %.1f m\n",
              m.rms_position_error_m, m.final_position_error_m, m.dr_rms_position_error_m,
              m.dr_final_position_error_m, m.distance_m);
  EXPECT_GT(m.dr_rms_position_error_m, 0.1);
  EXPECT_LT(m.rms_position_error_m, 0.5 * m.dr_rms_position_error_m);
  // The covariance grew with the distance driven.
  EXPECT_GT(runner.lastStep().covariance(kLocX, kLocX), 1e-4);
  ASSERT_TRUE(runner.lastStep().mouse_motion.has_value());
}

std::string constructionError(const RobotProfile& profile, EstimatorKind kind) {
  EstimatorRunnerConfig config;
  config.kind = kind;
  try {
    EstimatorRunner runner(WorldMap{}, profile, Pose2{}, config);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

TEST(EstimatorRunner, TheCasterEkfNeedsAThreeCasterRobotAndTheWheelEncoderKindsRefuseOne) {
  EXPECT_EQ(parseEstimatorKind("ekf-caster"), EstimatorKind::kStereoEkfCaster);
  EXPECT_TRUE(usesStereo(EstimatorKind::kStereoEkfCaster));
  EXPECT_FALSE(usesStereo(EstimatorKind::kMouseOdometry));
  const std::string refused = constructionError(thesisRobot(), EstimatorKind::kStereoEkfCaster);
  EXPECT_NE(refused.find("three_caster"), std::string::npos) << refused;
  EXPECT_NE(refused.find("/drive/type"), std::string::npos) << refused;
  for (EstimatorKind k :
       {EstimatorKind::kStereoEkf, EstimatorKind::kDeadReckoning, EstimatorKind::kEncoderGyro}) {
    const std::string e = constructionError(casterRobot(), k);
    EXPECT_NE(e.find("use 'ekf-caster'"), std::string::npos) << toString(k) << ": " << e;
  }
  EXPECT_EQ(constructionError(casterRobot(), EstimatorKind::kStereoEkfCaster), "");
  EstimatorRunnerConfig bad;
  bad.kind = EstimatorKind::kStereoEkfCaster;
  bad.caster_lambda = -1.0;
  EXPECT_THROW(EstimatorRunner(WorldMap{}, casterRobot(), Pose2{}, bad), std::invalid_argument);
}

// Fed every 1 ms sample, the caster estimator's dead reckoning is the robot's own J+ odometry
// (the simulator's odometry_pose); fed one sample in 20 (as the GUI sees one per frame) the
// interval is split into 1 ms periods at interpolated steering and lands within millimetres.
TEST(EstimatorRunner, CasterDeadReckoningIsTheRobotsOwnLeastSquaresOdometryAtAnySampleRate) {
  WorldMap map;  // an open floor: no echoes, prediction only
  map.start = {0.0, 0.0, 0.0};
  SimConfig sim_config;
  sim_config.dt_s = 0.001;
  Simulator sim(map, casterRobot(), sim_config);
  EstimatorRunnerConfig config;
  config.kind = EstimatorKind::kStereoEkfCaster;
  // The first sample is the runners' baseline: they start from the robot's odometry there.
  TelemetrySample sample;
  sim.step(sample);
  EstimatorRunner every(map, casterRobot(), sample.odometry_pose, config);
  EstimatorRunner sparse(map, casterRobot(), sample.odometry_pose, config);
  every.feed(sample);
  sparse.feed(sample);
  const std::vector<Vec2> square = {{2, 0}, {2, 2}, {0, 2}, {0, 0}};
  std::size_t target = 0;
  for (long k = 0; target < square.size() && k < 200'000; ++k) {
    const Vec2 to_goal = square[target] - sim.truePose().position();
    if (to_goal.norm() < 0.05) {
      ++target;
      continue;
    }
    const double heading_error =
        wrapAngle(std::atan2(to_goal.y(), to_goal.x()) - sim.truePose().theta);
    sim.setCommand(
        {std::abs(heading_error) > 0.15 ? 0.0 : 0.3, std::clamp(2.0 * heading_error, -0.8, 0.8)});
    sim.step(sample);
    every.feed(sample);
    if (k % 20 == 19)
      sparse.feed(sample);
  }
  ASSERT_EQ(target, square.size());
  sparse.feed(sample);
  const Pose2& odometry = sim.odometryPose();
  const Pose2& dr = every.lastStep().dead_reckoning;
  EXPECT_LT((dr.position() - odometry.position()).norm(), 1e-6);
  EXPECT_NEAR(wrapAngle(dr.theta - odometry.theta), 0.0, 1e-6);
  // Without updates the estimate is the dead reckoning, and both drifted from the truth.
  EXPECT_LT((every.lastStep().estimate.position() - dr.position()).norm(), 1e-9);
  EXPECT_GT((dr.position() - sim.truePose().position()).norm(), 0.01);
  const Pose2& coarse = sparse.lastStep().dead_reckoning;
  EXPECT_LT((coarse.position() - odometry.position()).norm(), 0.005);
  EXPECT_NEAR(wrapAngle(coarse.theta - odometry.theta), 0.0, degToRad(0.2));
  // Every 1 ms period was predicted in both, and the residual feeds the adaptive noise.
  EXPECT_NEAR(static_cast<double>(sparse.metrics().caster_periods),
              static_cast<double>(every.metrics().caster_periods), 2.0);
  EXPECT_GT(every.metrics().mean_caster_residual_rad, 0.0);
  EXPECT_GT(every.lastStep().covariance(kLocX, kLocX), 1e-6);
}

}  // namespace
}  // namespace irgs
