#include "core/calibration/umbmark_square.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "core/calibration/umbmark_run.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulated_robot.hpp"

namespace irgs {
namespace {

RobotProfile p3dx() {
  const RobotProfileResult r = loadRobotProfileFile(std::filesystem::path(IRGS_SOURCE_DIR) /
                                                    "resources/robots/pioneer_p3dx.json");
  if (!r.ok())
    throw std::runtime_error("cannot load the P3-DX profile");
  RobotProfile profile = *r.profile;
  profile.sonars.clear();  // an empty floor: the sensors do not move the robot
  profile.bumpers.clear();
  profile.proximity.clear();
  return profile;
}

// Drives one square through the Robot interface, as the GUI session does for a linked robot:
// every sample goes to the behaviour, its answer is the next command.
UmbmarkSquareBehaviour driveSquare(Robot& robot, UmbmarkDirection direction) {
  UmbmarkSquareConfig config;
  config.direction = direction;
  UmbmarkSquareBehaviour behaviour(robot.profile(), config);
  for (int i = 0; i < 100000 && !behaviour.status().finished; ++i)
    for (const TelemetrySample& s : robot.update(0.01))
      robot.drive(behaviour.onSample(s));
  return behaviour;
}

// The behaviour on the Robot interface gives the same return errors as the simulated procedure
// (same driver, same odometry, same injected robot): what the wizard measures on a linked robot
// is what the acceptance test of the procedure measures.
TEST(UmbmarkSquare, DrivenThroughTheRobotInterfaceItReturnsWhereTheOdometryStarted) {
  const RobotProfile profile = p3dx();
  UmbmarkInjection injection;
  injection.wheel_diameter_ratio = 1.01;
  injection.wheelbase_scale = 1.03;
  UmbmarkRunConfig run_config;
  run_config.runs_per_direction = 1;
  const UmbmarkSimulation reference =
      runUmbmarkInSimulator(profile, injection, profile, run_config);
  ASSERT_TRUE(reference.ok);
  ASSERT_EQ(reference.trials.size(), 2u);

  for (const UmbmarkTrial& trial : reference.trials) {
    SimConfig sim_config;
    sim_config.odometry.left_scale = 2.0 / (injection.wheel_diameter_ratio + 1.0);
    sim_config.odometry.right_scale =
        2.0 * injection.wheel_diameter_ratio / (injection.wheel_diameter_ratio + 1.0);
    sim_config.odometry.wheelbase_scale = injection.wheelbase_scale;
    WorldMap floor;
    floor.start = Pose2{1.0, 2.0, 0.5};  // the start frame is where the robot stands
    SimulatedRobot robot(floor, profile, sim_config);
    const UmbmarkSquareBehaviour b = driveSquare(robot, trial.direction);
    ASSERT_TRUE(b.status().finished);
    EXPECT_FALSE(b.status().failed) << b.status().message;
    EXPECT_LT(b.odometryPose().position().norm(), 0.002);
    ASSERT_TRUE(b.truePose().has_value());
    const Vec2 error = b.truePose()->position() - b.odometryPose().position();
    EXPECT_GT(error.norm(), 0.5) << toString(trial.direction);  // the injected errors show
    EXPECT_LT((error - trial.error_m).norm(), 0.02)
        << toString(trial.direction) << ": " << error.transpose() << " vs "
        << trial.error_m.transpose();
  }
}

TEST(UmbmarkSquare, ATimeLimitEndsTheRunAsAFailureAndBadInputThrows) {
  const RobotProfile profile = p3dx();
  UmbmarkSquareConfig config;
  config.max_run_s = 5.0;
  UmbmarkSquareBehaviour behaviour(profile, config);
  SimulatedRobot robot(WorldMap{}, profile);
  for (int i = 0; i < 1000 && !behaviour.status().finished; ++i)
    for (const TelemetrySample& s : robot.update(0.01))
      robot.drive(behaviour.onSample(s));
  EXPECT_TRUE(behaviour.status().failed);
  EXPECT_EQ(behaviour.onSample(TelemetrySample{}), VelocityCommand{});

  config.side_m = 0.0;
  EXPECT_THROW(UmbmarkSquareBehaviour(profile, config), std::invalid_argument);
  RobotProfile no_wheelbase = profile;
  no_wheelbase.drive.wheelbase_m = 0.0;
  EXPECT_THROW(UmbmarkSquareBehaviour(no_wheelbase, UmbmarkSquareConfig{}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
