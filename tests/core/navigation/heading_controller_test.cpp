#include "core/navigation/heading_controller.hpp"

#include <gtest/gtest.h>

namespace irgs {
namespace {

TEST(HeadingController, ATargetOnTheLeftTurnsCounterClockwise) {
  // A002-7: alpha = atan2(y, x), w = k alpha; a target at +y (left) gives w > 0.
  HeadingControlParams p;
  p.k_theta = 2.0;
  EXPECT_NEAR(moveVectorAngle(Vec2(1.0, 1.0)), kPi / 4, 1e-12);
  const VelocityCommand c = trackMoveVector(p, Vec2(1.0, 0.2), 0.5);
  EXPECT_GT(c.angular_radps, 0.0);
  EXPECT_NEAR(c.angular_radps, 2.0 * std::atan2(0.2, 1.0), 1e-12);
  EXPECT_LT(trackMoveVector(p, Vec2(1.0, -0.2), 0.5).angular_radps, 0.0);
}

TEST(HeadingController, SlowsWithTheHeadingErrorAndTurnsOnTheSpotWhenTheTargetIsBehind) {
  HeadingControlParams p;
  EXPECT_NEAR(trackMoveVector(p, Vec2(1.0, 0.0), 0.5).linear_mps, 0.5, 1e-12);
  const double v45 = trackMoveVector(p, Vec2(1.0, 1.0), 0.5).linear_mps;
  EXPECT_NEAR(v45, 0.25, 1e-12);  // cos^2(45 deg)
  const VelocityCommand back = trackMoveVector(p, Vec2(-1.0, 0.1), 0.5);
  EXPECT_EQ(back.linear_mps, 0.0);
  EXPECT_NE(back.angular_radps, 0.0);
  EXPECT_LE(std::abs(back.angular_radps), p.max_turn_rate_radps);
}

TEST(HeadingController, WheelSpeedsUseTheFullWheelSeparation) {
  // A002-4: v_r = v + w B / 2 with B the full track; (12) w = (v_r - v_l) / B gives w back.
  const WheelCommand w = wheelSpeedsFor(0.5, 1.0, 0.4);
  EXPECT_NEAR(w.left_mps, 0.3, 1e-12);
  EXPECT_NEAR(w.right_mps, 0.7, 1e-12);
  const VelocityCommand back = bodyVelocityFrom(w, 0.4);
  EXPECT_NEAR(back.linear_mps, 0.5, 1e-12);
  EXPECT_NEAR(back.angular_radps, 1.0, 1e-12);
}

}  // namespace
}  // namespace irgs
