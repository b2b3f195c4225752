#include "core/robot/teleop_mapping.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace irgs {
namespace {

MotionLimits limits() {
  MotionLimits l;
  l.max_speed_mps = 0.8;
  l.max_turn_rate_radps = 2.0;
  return l;
}

GamepadState held(double ly, double rx, bool deadman = true, bool turbo = false) {
  GamepadState s;
  s.axes[1] = ly;
  s.axes[2] = rx;
  if (deadman)
    s.buttons |= 1u << 9;
  if (turbo)
    s.buttons |= 1u << 10;
  return s;
}

TEST(TeleopMapping, TheDeadbandSwallowsSmallDeflectionsAndTheRestStartsAtZero) {
  EXPECT_EQ(shapeAxis(0.1, 0.12, 0.0), 0.0);
  EXPECT_EQ(shapeAxis(-0.12, 0.12, 0.0), 0.0);
  EXPECT_NEAR(shapeAxis(0.13, 0.12, 0.0), 0.01 / 0.88, 1e-12);  // no jump at the edge
  EXPECT_DOUBLE_EQ(shapeAxis(1.0, 0.12, 0.4), 1.0);
  EXPECT_DOUBLE_EQ(shapeAxis(-1.0, 0.12, 0.4), -1.0);
  EXPECT_DOUBLE_EQ(shapeAxis(3.0, 0.0, 0.0), 1.0);  // clamped
  EXPECT_EQ(shapeAxis(std::numeric_limits<double>::quiet_NaN(), 0.1, 0.0), 0.0);
  // Expo: half deflection gives less than half output, full still gives full.
  EXPECT_NEAR(shapeAxis(0.5, 0.0, 1.0), 0.125, 1e-12);
  EXPECT_NEAR(shapeAxis(0.5, 0.0, 0.4), 0.6 * 0.5 + 0.4 * 0.125, 1e-12);
}

TEST(TeleopMapping, WithoutTheDeadManTheRobotDoesNotMove) {
  TeleopMappingConfig config;
  EXPECT_EQ(mapGamepad(held(-1.0, 0.0, false), config, limits()), VelocityCommand{});
  config.deadman_button = -1;  // no dead-man configured: the stick alone drives
  EXPECT_GT(mapGamepad(held(-1.0, 0.0, false), config, limits()).linear_mps, 0.0);
}

TEST(TeleopMapping, StickUpDrivesForwardRightTurnsClockwiseWithinTheProfileLimits) {
  const TeleopMappingConfig config;
  const VelocityCommand forward = mapGamepad(held(-1.0, 0.0), config, limits());
  EXPECT_DOUBLE_EQ(forward.linear_mps, 0.5 * 0.8);  // normal speed: half the profile's
  EXPECT_DOUBLE_EQ(forward.angular_radps, 0.0);
  const VelocityCommand right = mapGamepad(held(0.0, 1.0), config, limits());
  EXPECT_DOUBLE_EQ(right.angular_radps, -0.5 * 2.0);
  const VelocityCommand turbo = mapGamepad(held(1.0, -1.0, true, true), config, limits());
  EXPECT_DOUBLE_EQ(turbo.linear_mps, -0.8);  // full stick back with turbo: the profile's max
  EXPECT_DOUBLE_EQ(turbo.angular_radps, 2.0);
  // Remapped axes: the left stick alone (arcade).
  TeleopMappingConfig arcade;
  arcade.angular = {0, true};
  GamepadState s = held(0.0, 0.0);
  s.axes[0] = 1.0;
  EXPECT_LT(mapGamepad(s, arcade, limits()).angular_radps, 0.0);
  EXPECT_EQ(mapGamepad(s, config, limits()).angular_radps, 0.0);
}

TEST(TeleopMapping, TheStickOfThePadUsesTheSameShaping) {
  const VelocityCommand c = mapStick(0.0, -1.0, 0.1, 0.0, 0.3, 1.0);
  EXPECT_DOUBLE_EQ(c.linear_mps, 0.3);
  EXPECT_DOUBLE_EQ(c.angular_radps, 0.0);
  EXPECT_EQ(mapStick(0.05, 0.05, 0.1, 0.0, 0.3, 1.0), VelocityCommand{});
  EXPECT_DOUBLE_EQ(mapStick(-1.0, 0.0, 0.1, 0.0, 0.3, 1.0).angular_radps, 1.0);  // left = CCW
}

TEST(TeleopMapping, InvalidConfigurationsThrow) {
  TeleopMappingConfig c;
  validate(c);
  c.deadband = 1.0;
  EXPECT_THROW(validate(c), std::invalid_argument);
  c = {};
  c.expo = -0.1;
  EXPECT_THROW(validate(c), std::invalid_argument);
  c = {};
  c.linear.axis = GamepadState::kAxes;
  EXPECT_THROW(validate(c), std::invalid_argument);
  c = {};
  c.normal_fraction = 0.0;
  EXPECT_THROW(validate(c), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
