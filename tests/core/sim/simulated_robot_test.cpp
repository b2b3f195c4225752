#include "core/sim/simulated_robot.hpp"

#include <gtest/gtest.h>

#include "sim_test_support.hpp"

namespace irgs {
namespace {

SimulatedRobot makeRobot() {
  return SimulatedRobot(test::emptyWorld(), test::squareRobot(), test::exactConfig());
}

TEST(SimulatedRobot, AdvancesSimulatedTimeByWallTimeCarryingFractions) {
  SimulatedRobot robot = makeRobot();
  EXPECT_EQ(robot.update(0.015).size(), 1u);  // 1.5 steps owed: 1 now
  EXPECT_EQ(robot.update(0.015).size(), 2u);  // 0.5 + 1.5 = 2
  EXPECT_NEAR(robot.simulator().time_s(), 0.03, 1e-12);
  // Many small updates add up without drift.
  std::size_t steps = 0;
  for (int i = 0; i < 1000; ++i)
    steps += robot.update(0.0037).size();
  EXPECT_NEAR(static_cast<double>(steps), 370.0, 1.0);
}

TEST(SimulatedRobot, SpeedFactorScalesTime) {
  SimulatedRobot robot = makeRobot();
  robot.setSpeedFactor(4.0);
  EXPECT_EQ(robot.update(0.1).size(), 40u);
  robot.setSpeedFactor(0.5);
  EXPECT_EQ(robot.update(0.1).size(), 5u);
  EXPECT_THROW(robot.setSpeedFactor(-1.0), std::invalid_argument);
  EXPECT_THROW(robot.setSpeedFactor(std::nan("")), std::invalid_argument);
  EXPECT_DOUBLE_EQ(robot.speedFactor(), 0.5);
}

TEST(SimulatedRobot, SpeedZeroRunsTheMaximumStepsPerUpdate) {
  SimulatedRobot robot = makeRobot();
  robot.setSpeedFactor(0.0);
  EXPECT_EQ(robot.update(0.0).size(), static_cast<std::size_t>(SimulatedRobot::kDefaultMaxSteps));
  robot.setMaxStepsPerUpdate(7);
  EXPECT_EQ(robot.update(1.0).size(), 7u);
  EXPECT_THROW(robot.setMaxStepsPerUpdate(0), std::invalid_argument);
  // A finite speed beyond what "max" runs behaves as max.
  robot.setSpeedFactor(1e9);
  EXPECT_EQ(robot.update(1.0).size(), 7u);
}

TEST(SimulatedRobot, PausedRunsNothingButSingleStepStillSteps) {
  SimulatedRobot robot = makeRobot();
  robot.setPaused(true);
  EXPECT_TRUE(robot.paused());
  EXPECT_TRUE(robot.update(1.0).empty());
  robot.singleStep();
  robot.singleStep();
  const auto samples = robot.update(1.0);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_NEAR(samples[1].time_s, 0.02, 1e-12);
  robot.setPaused(false);
  EXPECT_EQ(robot.update(0.05).size(), 5u);
}

TEST(SimulatedRobot, IgnoresNegativeElapsedTimeAndDoesNotReplayLongStalls) {
  SimulatedRobot robot = makeRobot();
  EXPECT_TRUE(robot.update(-5.0).empty());
  EXPECT_TRUE(robot.update(std::nan("")).empty());
  EXPECT_EQ(robot.update(3600.0).size(), 100u);  // capped at kMaxWallStep_s = 1 s
}

TEST(SimulatedRobot, DrivesThroughTheRobotInterface) {
  SimulatedRobot sim = makeRobot();
  Robot& robot = sim;
  ASSERT_NE(robot.simulationControl(), nullptr);
  EXPECT_EQ(robot.profile().name, "square");
  EXPECT_NE(robot.describe().find("simulator"), std::string::npos);
  robot.drive({0.4, 0.0});
  const auto moving = robot.update(1.0);
  ASSERT_FALSE(moving.empty());
  EXPECT_GT(moving.back().true_pose->x, 0.2);
  robot.stop();
  robot.update(1.0);
  const double stopped_x = sim.simulator().truePose().x;
  robot.update(1.0);
  EXPECT_EQ(sim.simulator().truePose().x, stopped_x);
}

TEST(SimulatedRobot, SetMapReplacesTheWorldKeepingThePose) {
  SimulatedRobot robot = makeRobot();
  robot.drive({0.5, 0.0});
  robot.update(1.0);
  const Pose2 before = robot.simulator().truePose();
  robot.setMap(test::squareRoom(5.0));
  EXPECT_EQ(robot.simulator().truePose(), before);
  EXPECT_EQ(robot.simulator().map().name, "room");
  EXPECT_EQ(robot.simulator().world().segmentCount(), 4u);
}

}  // namespace
}  // namespace irgs
