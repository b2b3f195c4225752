#include "core/geometry/types.hpp"

#include <gtest/gtest.h>

namespace irgs {
namespace {

TEST(WrapAngle, MapsIntoHalfOpenIntervalWithPiIncluded) {
  EXPECT_DOUBLE_EQ(wrapAngle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrapAngle(-kPi), kPi);
  EXPECT_NEAR(wrapAngle(3.0 * kPi / 2.0), -kPi / 2.0, 1e-12);
  EXPECT_NEAR(wrapAngle(-7.0 * kPi / 2.0), kPi / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(wrapAngle(0.25), 0.25);
}

TEST(Pose2, ToWorldAndToBodyAreInverses) {
  const Pose2 pose{1.0, -2.0, 0.7};
  const Vec2 body{0.3, -0.4};
  const Vec2 back = pose.toBody(pose.toWorld(body));
  EXPECT_NEAR(back.x(), body.x(), 1e-12);
  EXPECT_NEAR(back.y(), body.y(), 1e-12);
}

TEST(Pose2, ForwardIsBodyXAndLeftIsBodyY) {
  const Pose2 facing_north{0.0, 0.0, kPi / 2.0};
  const Vec2 ahead = facing_north.toWorld({1.0, 0.0});
  const Vec2 left = facing_north.toWorld({0.0, 1.0});
  EXPECT_NEAR(ahead.y(), 1.0, 1e-12);
  EXPECT_NEAR(left.x(), -1.0, 1e-12);
}

TEST(Pose2, ComposeAppliesOtherInThisFrame) {
  const Pose2 a{1.0, 0.0, kPi / 2.0};
  const Pose2 c = a.compose({1.0, 0.0, kPi / 2.0});
  EXPECT_NEAR(c.x, 1.0, 1e-12);
  EXPECT_NEAR(c.y, 1.0, 1e-12);
  EXPECT_NEAR(c.theta, kPi, 1e-12);
}

TEST(Segment, LeftNormalPointsCounterClockwiseFromDirection) {
  const Segment s{{0.0, 0.0}, {2.0, 0.0}};
  EXPECT_NEAR(s.leftNormal().y(), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.length(), 2.0);
}

TEST(Box2, StartsEmptyAndGrowsToContainPoints) {
  Box2 b;
  EXPECT_TRUE(b.empty());
  b.extend(Vec2(1.0, 2.0));
  b.extend(Vec2(-1.0, 0.5));
  EXPECT_FALSE(b.empty());
  EXPECT_TRUE(b.contains({0.0, 1.0}));
  EXPECT_FALSE(b.contains({0.0, 3.0}));
}

}  // namespace
}  // namespace irgs
