// The three-caster robot of paper 000 in Simulator (caster_drive_sim.hpp): which profiles
// report caster encoders, what the encoders count, how the trailing casters swivel, and the
// robot's own J+ dead reckoning with and without the profile's wheel errors.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/estimation/caster_profile.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/caster_drive_sim.hpp"
#include "core/sim/simulator.hpp"
#include "sim_test_support.hpp"

namespace irgs {
namespace {

RobotProfile casterRobot() {
  const RobotProfileResult loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/caster3_000.json");
  EXPECT_TRUE(loaded.ok());
  return loaded.profile.value_or(RobotProfile{});
}

SimConfig errorFree() {
  SimConfig c = test::exactConfig();
  c.caster_errors = CasterErrorModel{};
  return c;
}

double positionError(const Simulator& sim) {
  return (sim.odometryPose().position() - sim.truePose().position()).norm();
}

// Drives forward, a left arc, a spin on the spot and forward again (about 4 m).
void driveTour(Simulator& sim) {
  const struct {
    VelocityCommand command;
    int steps;
  } legs[] = {{{0.3, 0.0}, 400}, {{0.3, 0.4}, 600}, {{0.0, 0.8}, 300}, {{0.3, 0.0}, 400}};
  for (const auto& leg : legs) {
    sim.setCommand(leg.command);
    for (int i = 0; i < leg.steps; ++i)
      sim.step();
  }
}

TEST(SimulatorCaster, OnlyAThreeCasterProfileReportsCasterEncoders) {
  Simulator plain(WorldMap{}, test::squareRobot(), test::exactConfig());
  EXPECT_FALSE(plain.step().casters.has_value());
  Simulator caster(WorldMap{}, casterRobot(), errorFree());
  caster.setCommand({0.3, 0.0});
  TelemetrySample s;
  for (int i = 0; i < 100; ++i)
    caster.step(s);
  ASSERT_TRUE(s.casters.has_value());
  // No left/right wheels: the differential encoders stay at zero, the casters count.
  EXPECT_EQ(s.left_ticks, 0);
  EXPECT_EQ(s.right_ticks, 0);
  // Straight ahead with the casters trailing straight: every drive wheel turns by path / r.
  const double ticks_per_rad = caster.profile().drive.ticksPerWheelRad();
  const double travelled = caster.truePose().x - caster.map().start.x;
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(static_cast<double>(s.casters->drive_ticks[i]) / ticks_per_rad, travelled / 0.05,
                2.0 / ticks_per_rad);
    EXPECT_EQ(s.casters->steering_ticks[i], 0);
  }
}

TEST(SimulatorCaster, TrailingCastersSwivelIntoTheirEquilibriumWhenTurningOnTheSpot) {
  Simulator sim(WorldMap{}, casterRobot(), errorFree());
  sim.setCommand({0.0, 1.0});  // counter-clockwise, clamped to the profile's 60 deg/s
  TelemetrySample s;
  for (int i = 0; i < 500; ++i)
    sim.step(s);
  const CasterDriveGeometry g = *casterGeometryFromProfile(sim.profile()).geometry;
  const double ticks_per_rad = sim.profile().drive.ticksPerWheelRad();
  // Row 2 of (26) with V = 0: phi' = Omega (d cos(phi - alpha) / eps - 1) = 0 at
  // cos(phi - alpha) = eps / d, stable on the side where sin(phi - alpha) > 0.
  const double expected_offset = std::acos(g.offset_m / g.casters[0].d_m);
  for (std::size_t i = 0; i < 3; ++i) {
    const double measured = static_cast<double>(s.casters->steering_ticks[i]) / ticks_per_rad;
    EXPECT_NEAR(wrapAngle(measured - g.casters[i].alpha_rad), expected_offset, degToRad(1.0))
        << "caster " << i;
  }
  // The robot spun on the spot and its own J+ dead reckoning says so.
  EXPECT_LT(positionError(sim), 0.002);
  EXPECT_NEAR(wrapAngle(sim.odometryPose().theta - sim.truePose().theta), 0.0, degToRad(0.2));
}

TEST(SimulatorCaster, ErrorFreeEncodersGiveTheTruePathThroughTheLeastSquaresOdometry) {
  Simulator sim(WorldMap{}, casterRobot(), errorFree());
  driveTour(sim);
  EXPECT_GT((sim.truePose().position() - Vec2(sim.map().start.x, sim.map().start.y)).norm(), 1.5);
  EXPECT_LT(positionError(sim), 0.005);  // encoder quantisation only
  EXPECT_NEAR(wrapAngle(sim.odometryPose().theta - sim.truePose().theta), 0.0, degToRad(0.3));
}

TEST(SimulatorCaster, TheProfilesWheelErrorsMakeItsDeadReckoningDriftAndAreItsOwnStream) {
  const RobotProfile robot = casterRobot();
  const CasterErrorResult errors = casterErrorsFromProfile(robot);
  ASSERT_TRUE(errors.errors.has_value());
  EXPECT_DOUBLE_EQ(errors.errors->radius_scale[0], 1.01);
  EXPECT_DOUBLE_EQ(errors.errors->drive_slip_stddev, 0.005);

  Simulator exact(WorldMap{}, robot, errorFree());
  SimConfig with_errors = test::exactConfig();  // caster_errors empty: the profile's
  Simulator noisy(WorldMap{}, robot, with_errors);
  driveTour(exact);
  driveTour(noisy);
  EXPECT_GT(positionError(noisy), 5.0 * positionError(exact) + 0.01);
  // The wheel errors do not change the truth (the body follows the command).
  EXPECT_LT((noisy.truePose().position() - exact.truePose().position()).norm(), 1e-12);

  // Same seed, same samples; another seed, other encoder noise.
  Simulator again(WorldMap{}, robot, with_errors);
  driveTour(again);
  EXPECT_EQ(again.odometryPose().x, noisy.odometryPose().x);
  with_errors.seed = 2;
  Simulator other(WorldMap{}, robot, with_errors);
  driveTour(other);
  EXPECT_NE(other.odometryPose().x, noisy.odometryPose().x);
}

TEST(SimulatorCaster, BadSimulatedErrorsInTheProfileAreDiagnosticsAndTheSimulatorRefusesThem) {
  RobotProfile robot = casterRobot();
  robot.drive.extra["three_caster"]["simulated_errors"] = {{"radius_scale", {1.0, 0.0, 1.0}},
                                                           {"drive_slip_stddev", -1.0}};
  const CasterErrorResult r = casterErrorsFromProfile(robot);
  EXPECT_FALSE(r.errors.has_value());
  ASSERT_EQ(r.diagnostics.size(), 2u);
  EXPECT_EQ(r.diagnostics[0].field, "/drive/three_caster/simulated_errors/radius_scale/1");
  EXPECT_THROW(Simulator(WorldMap{}, robot, test::exactConfig()), std::invalid_argument);
  // Without the geometry the simulator cannot drive the robot at all.
  RobotProfile no_geometry = casterRobot();
  no_geometry.drive.extra.erase("three_caster");
  EXPECT_THROW(Simulator(WorldMap{}, no_geometry, test::exactConfig()), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
