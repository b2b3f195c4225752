// Sonar, proximity and determinism of the Simulator's sensors.
#include <gtest/gtest.h>

#include <cmath>

#include "core/sim/simulator.hpp"
#include "sim_test_support.hpp"

namespace irgs {
namespace {

using test::exactConfig;
using test::forwardSonar;
using test::squareRobot;
using test::wall;

// A robot with one forward sonar (mount x = 0.1) in a world of the given walls.
Simulator sonarSim(std::vector<Wall> walls, SimConfig config = exactConfig(),
                   SonarSpec sonar = forwardSonar()) {
  WorldMap world;
  world.walls = std::move(walls);
  RobotProfile robot = squareRobot();
  robot.body_outline.clear();  // a point robot: these tests are about sensing, not contact
  robot.sonars = {sonar};
  return Simulator(world, robot, config);
}

// Steps until `count` sonar readings have been collected.
std::vector<SonarReading> readings(Simulator& sim, int count) {
  std::vector<SonarReading> out;
  while (static_cast<int>(out.size()) < count) {
    for (const auto& r : sim.step().sonar)
      out.push_back(r);
  }
  return out;
}

TEST(SimulatorSonar, MeasuresTheRangeToAKnownWall) {
  Simulator sim = sonarSim({wall({2.0, -1.0}, {2.0, 1.0})});
  for (const auto& r : readings(sim, 5)) {
    EXPECT_TRUE(r.echo);
    EXPECT_EQ(r.sensor, 0);
    EXPECT_NEAR(r.range_m, 1.9, 1e-12);  // the perpendicular (central) ray is the nearest
  }
}

TEST(SimulatorSonar, FiresAtItsRate) {
  Simulator sim = sonarSim({wall({2.0, -1.0}, {2.0, 1.0})});
  int fired = 0;
  for (int i = 0; i < 300; ++i)
    fired += static_cast<int>(sim.step().sonar.size());
  EXPECT_EQ(fired, 30);  // 10 Hz for 3 s
}

TEST(SimulatorSonar, TheBeamConeReportsTheNearestReturnOffAxis) {
  // A wall 3 m ahead and a short post 1 m ahead, 0.15 m to the side: outside the central ray
  // but inside a 25 degree cone (half angle 12.5 degrees: 0.22 m at 1 m).
  const std::vector<Wall> walls = {wall({3.1, -2.0}, {3.1, 2.0}), wall({1.1, 0.1}, {1.1, 0.2})};
  Simulator wide = sonarSim(walls, exactConfig(), forwardSonar(25.0));
  const SonarReading r = readings(wide, 1)[0];
  ASSERT_TRUE(r.echo);
  EXPECT_GT(r.range_m, 1.0);
  EXPECT_LT(r.range_m, 1.0 / std::cos(degToRad(12.5)) + 1e-9);
  // A 5 degree cone misses the post and sees the wall.
  Simulator narrow = sonarSim(walls, exactConfig(), forwardSonar(5.0));
  EXPECT_NEAR(readings(narrow, 1)[0].range_m, 3.0, 1e-12);
}

TEST(SimulatorSonar, GrazingIncidenceGivesNoEcho) {
  // A wall crossing the beam axis 0.9 m ahead at 12 degrees to it: incidence 78 > 60 degrees.
  const double slope = std::tan(degToRad(12.0));
  Simulator grazing =
      sonarSim({wall({0.2, -0.8 * slope}, {4.0, 3.0 * slope})}, exactConfig(), forwardSonar(5.0));
  for (const auto& r : readings(grazing, 5)) {
    EXPECT_FALSE(r.echo);
    EXPECT_EQ(r.range_m, 4.0);  // max range when nothing echoes
  }
  // A wall at 45 degrees (incidence 45 +- 2.5) echoes; the nearest ray is the cone's edge
  // ray at -2.5 degrees: 0.1 + d (cos a - sin a) = 1.5 on the line x - y = 1.5.
  Simulator oblique = sonarSim({wall({0.5, -1.0}, {2.5, 1.0})}, exactConfig(), forwardSonar(5.0));
  const SonarReading r = readings(oblique, 1)[0];
  EXPECT_TRUE(r.echo);
  const double a = degToRad(-2.5);
  EXPECT_NEAR(r.range_m, 1.4 / (std::cos(a) - std::sin(a)), 1e-9);
}

TEST(SimulatorSonar, ASurfaceBeyondMaxRangeGivesNoEchoAndACloseOneReadsMinRange) {
  Simulator far = sonarSim({wall({4.5, -1.0}, {4.5, 1.0})});
  EXPECT_FALSE(readings(far, 1)[0].echo);
  Simulator close = sonarSim({wall({0.12, -1.0}, {0.12, 1.0})});
  const SonarReading r = readings(close, 1)[0];
  EXPECT_TRUE(r.echo);
  EXPECT_EQ(r.range_m, 0.05);  // 0.02 m is inside the blanking distance
}

TEST(SimulatorSonar, DropsEchoesWithTheConfiguredProbability) {
  SimConfig config = exactConfig();
  config.sonar.dropout_probability = 0.3;
  Simulator sim = sonarSim({wall({2.0, -1.0}, {2.0, 1.0})}, config);
  int missing = 0;
  const auto all = readings(sim, 2000);
  for (const auto& r : all)
    missing += !r.echo;
  EXPECT_NEAR(missing / 2000.0, 0.3, 0.04);

  config.sonar.dropout_probability = 1.0;
  Simulator deaf = sonarSim({wall({2.0, -1.0}, {2.0, 1.0})}, config);
  for (const auto& r : readings(deaf, 50))
    EXPECT_FALSE(r.echo);
}

TEST(SimulatorSonar, RangeNoiseGrowsWithRange) {
  auto stddevAt = [](double wall_x) {
    SimConfig config = exactConfig();
    config.sonar.range_stddev_m = 0.01;
    config.sonar.range_stddev_per_m = 0.02;
    Simulator sim = sonarSim({wall({wall_x, -2.0}, {wall_x, 2.0})}, config, forwardSonar(1.0));
    const double truth = wall_x - 0.1;
    double sum = 0.0, sum2 = 0.0;
    const auto all = readings(sim, 4000);
    for (const auto& r : all) {
      sum += r.range_m - truth;
      sum2 += (r.range_m - truth) * (r.range_m - truth);
    }
    const double mean = sum / 4000.0;
    EXPECT_NEAR(mean, 0.0, 0.005);
    return std::sqrt(sum2 / 4000.0 - mean * mean);
  };
  EXPECT_NEAR(stddevAt(1.1), 0.01 + 0.02 * 1.0, 0.002);
  EXPECT_NEAR(stddevAt(3.1), 0.01 + 0.02 * 3.0, 0.004);
}

TEST(SimulatorSonar, SeesARasterWall) {
  WorldMap world;
  RasterLayer layer;
  RasterMap& r = layer.raster;
  r.width = 100;
  r.height = 100;
  r.resolution_m = 0.03;
  r.origin = {-1.5, -1.5, 0.0};
  r.cells.assign(10000, RasterMap::kFree);
  for (int row = 0; row < 100; ++row)
    r.at(90, row) = RasterMap::kOccupied;  // x = 1.2
  world.raster = layer;
  RobotProfile robot = squareRobot();
  robot.sonars = {forwardSonar()};
  Simulator sim(world, robot, exactConfig());
  const SonarReading reading = readings(sim, 1)[0];
  ASSERT_TRUE(reading.echo);
  EXPECT_NEAR(reading.range_m, 1.1, 1e-9);
}

TEST(SimulatorProximity, ReadsTheDistanceToANearWallAndMaxRangeOtherwise) {
  WorldMap world;
  world.walls = {wall({0.4, -1.0}, {0.4, 1.0})};
  RobotProfile robot = squareRobot();
  ProximitySpec front;
  front.mount = {0.15, 0.0, 0.0};
  front.max_range_m = 0.3;
  ProximitySpec rear = front;
  rear.mount = {-0.15, 0.0, kPi};
  robot.proximity = {front, rear};
  SimConfig config = exactConfig();
  config.proximity_stddev_m = 0.002;
  Simulator sim(world, robot, config);
  TelemetrySample sample;
  for (int i = 0; i < 10; ++i)
    sim.step(sample);
  ASSERT_EQ(sample.proximity_m.size(), 2u);
  EXPECT_NEAR(sample.proximity_m[0], 0.25, 0.01);
  EXPECT_NE(sample.proximity_m[0], 0.25);  // noisy
  EXPECT_EQ(sample.proximity_m[1], 0.3);   // nothing behind
}

// Everything a sample carries, compared exactly.
void expectSameSample(const TelemetrySample& a, const TelemetrySample& b) {
  ASSERT_EQ(a.time_s, b.time_s);
  ASSERT_EQ(a.odometry_pose, b.odometry_pose);
  ASSERT_EQ(a.true_pose, b.true_pose);
  ASSERT_EQ(a.left_ticks, b.left_ticks);
  ASSERT_EQ(a.right_ticks, b.right_ticks);
  ASSERT_EQ(a.bumpers, b.bumpers);
  ASSERT_EQ(a.proximity_m, b.proximity_m);
  ASSERT_EQ(a.sonar.size(), b.sonar.size());
  for (std::size_t i = 0; i < a.sonar.size(); ++i) {
    ASSERT_EQ(a.sonar[i].sensor, b.sonar[i].sensor);
    ASSERT_EQ(a.sonar[i].range_m, b.sonar[i].range_m);
    ASSERT_EQ(a.sonar[i].echo, b.sonar[i].echo);
  }
}

std::vector<TelemetrySample> noisyRun(std::uint64_t seed) {
  WorldMap world = test::squareRoom(2.0);
  world.walls.push_back(wall({0.5, 0.8}, {1.2, 1.4}));
  RobotProfile robot = squareRobot();
  for (int i = 0; i < 4; ++i) {
    SonarSpec s = forwardSonar(25.0);
    s.mount.theta = i * kPi / 2.0;
    robot.sonars.push_back(s);
  }
  ProximitySpec ir;
  ir.mount = {0.15, 0.0, 0.0};
  robot.proximity = {ir};
  SimConfig config;  // default noise
  config.seed = seed;
  config.odometry.slip_stddev = 0.02;
  Simulator sim(world, robot, config);
  std::vector<TelemetrySample> out;
  for (int i = 0; i < 1500; ++i) {
    sim.setCommand({0.3, i < 700 ? 0.4 : -0.6});
    out.push_back(sim.step());
  }
  return out;
}

TEST(SimulatorDeterminism, SameSeedGivesIdenticalSamples) {
  const auto a = noisyRun(99), b = noisyRun(99);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    expectSameSample(a[i], b[i]);
}

TEST(SimulatorDeterminism, DifferentSeedsGiveDifferentNoise) {
  const auto a = noisyRun(1), b = noisyRun(2);
  int differing_sonar = 0, compared = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t k = 0; k < std::min(a[i].sonar.size(), b[i].sonar.size()); ++k) {
      ++compared;
      differing_sonar += a[i].sonar[k].range_m != b[i].sonar[k].range_m;
    }
  }
  EXPECT_GT(compared, 100);
  EXPECT_GT(differing_sonar, compared / 2);
  EXPECT_NE(a.back().true_pose, b.back().true_pose);
}

}  // namespace
}  // namespace irgs

namespace irgs {
namespace {

// A point robot with the paper-004 rig: right and left sensors 0.2 m apart, 800 cpi.
RobotProfile mouseRigRobot() {
  RobotProfile robot = test::squareRobot();
  robot.body_outline.clear();
  robot.drive.extra["mouse_sensors"] = {
      {"counts_per_inch", 800.0},
      {"right", {{"x_m", 0.0}, {"y_m", -0.1}, {"heading_deg", 0.0}}},
      {"left", {{"x_m", 0.0}, {"y_m", 0.1}, {"heading_deg", 0.0}}}};
  return robot;
}

TEST(SimulatorMouse, OnlyARobotWithAFloorSensorRigReportsCounts) {
  Simulator plain(WorldMap{}, test::squareRobot(), test::exactConfig());
  EXPECT_FALSE(plain.step().mouse.has_value());
  SimConfig off = test::exactConfig();
  off.mouse_sensors = false;
  Simulator disabled(WorldMap{}, mouseRigRobot(), off);
  EXPECT_FALSE(disabled.step().mouse.has_value());
  Simulator with(WorldMap{}, mouseRigRobot(), test::exactConfig());
  EXPECT_TRUE(with.step().mouse.has_value());
}

TEST(SimulatorMouse, CountsFollowTheTrueMotion) {
  Simulator sim(WorldMap{}, mouseRigRobot(), test::exactConfig());
  const double metres_per_count = 0.0254 / 800.0;
  // Forward: both sensors count the same forward travel, nothing sideways.
  sim.setCommand({0.2, 0.0});
  // The counts are cumulative since the start.
  std::int64_t right_dx = 0, left_dx = 0, dy = 0;
  const double x0 = sim.truePose().x;
  for (int i = 0; i < 300; ++i) {
    const MouseReading m = *sim.step().mouse;
    EXPECT_GE(m.right.dx, right_dx);  // never counts backwards while driving forwards
    right_dx = m.right.dx;
    left_dx = m.left.dx;
    dy = m.right.dy + m.left.dy;
    EXPECT_EQ(m.right.status, MouseStatus::kTracking);
  }
  const double travelled = sim.truePose().x - x0;
  EXPECT_NEAR(static_cast<double>(right_dx) * metres_per_count, travelled, 2 * metres_per_count);
  EXPECT_NEAR(static_cast<double>(left_dx) * metres_per_count, travelled, 2 * metres_per_count);
  EXPECT_EQ(dy, 0);
  // Spinning in place (counter-clockwise): the right sensor moves forward, the left backward.
  sim.halt();
  sim.setCommand({0.0, 1.0});
  const std::int64_t right_before = right_dx, left_before = left_dx;
  for (int i = 0; i < 100; ++i) {
    const MouseReading m = *sim.step().mouse;
    right_dx = m.right.dx - right_before;
    left_dx = m.left.dx - left_before;
  }
  EXPECT_GT(right_dx, 100);
  EXPECT_NEAR(static_cast<double>(left_dx), -static_cast<double>(right_dx), 2.0);
}

TEST(SimulatorMouse, LiftedSensorsReportNothingAndAddingTheRigChangesNoOtherOutput) {
  SimConfig lifted = test::exactConfig();
  lifted.mouse_floor_gap_m = 0.01;  // 1 cm: far above the 2 mm lift-off height
  Simulator sim(WorldMap{}, mouseRigRobot(), lifted);
  sim.setCommand({0.2, 0.0});
  for (int i = 0; i < 50; ++i) {
    const MouseReading m = *sim.step().mouse;
    EXPECT_EQ(m.right.status, MouseStatus::kLifted);
    EXPECT_EQ(m.right.dx, 0);
  }
  // Own random stream: with noisy mice every other output is what it is without them.
  SimConfig noisy;
  noisy.seed = 9;
  noisy.mouse_noise.relative_stddev = 0.05;
  Simulator a(WorldMap{}, mouseRigRobot(), noisy);
  noisy.mouse_sensors = false;
  Simulator b(WorldMap{}, mouseRigRobot(), noisy);
  a.setCommand({0.2, 0.3});
  b.setCommand({0.2, 0.3});
  for (int i = 0; i < 200; ++i) {
    const TelemetrySample sa = a.step(), sb = b.step();
    ASSERT_EQ(sa.left_ticks, sb.left_ticks);
    ASSERT_EQ(sa.odometry_pose.x, sb.odometry_pose.x);
    ASSERT_EQ(sa.true_pose->theta, sb.true_pose->theta);
  }
}

}  // namespace
}  // namespace irgs
