#include "core/estimation/trajectory_compare.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace irgs {
namespace {

TEST(TrajectoryCompare, InterpolatesLinearlyAndAlongTheShortestArc) {
  const std::vector<TimedPose> b = {{0.0, {0.0, 0.0, degToRad(170.0)}},
                                    {1.0, {1.0, 2.0, degToRad(-170.0)}}};
  Pose2 p;
  ASSERT_TRUE(interpolatePose(b, 0.5, p));
  EXPECT_NEAR(p.x, 0.5, 1e-12);
  EXPECT_NEAR(p.y, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(p.theta), kPi, 1e-12);  // through 180, not through 0
  EXPECT_TRUE(interpolatePose(b, 1.0, p));
  EXPECT_EQ(p.x, 1.0);
  EXPECT_FALSE(interpolatePose(b, 1.5, p));
  EXPECT_FALSE(interpolatePose(b, -0.1, p));
  EXPECT_FALSE(interpolatePose({}, 0.0, p));
}

TEST(TrajectoryCompare, ReportsRmsMaxAndFinalDifferences) {
  std::vector<TimedPose> a, b;
  for (int i = 0; i <= 4; ++i) {
    const double t = i;
    a.push_back({t, {t, 0.0, 0.0}});
    b.push_back({t, {t, i < 4 ? 0.3 : 0.4, degToRad(i)}});  // 0.3 m off, then 0.4 m
  }
  a.push_back({9.0, {0.0, 0.0, 0.0}});  // outside b's span: not compared
  const TrajectoryDifference d = compareTrajectories(a, b);
  EXPECT_EQ(d.compared, 5u);
  EXPECT_NEAR(d.rms_position_m, std::sqrt((4 * 0.09 + 0.16) / 5.0), 1e-12);
  EXPECT_NEAR(d.max_position_m, 0.4, 1e-12);
  EXPECT_NEAR(d.final_position_m, 0.4, 1e-12);
  EXPECT_NEAR(d.max_heading_rad, degToRad(4.0), 1e-12);
  EXPECT_NEAR(d.final_heading_rad, degToRad(4.0), 1e-12);
  EXPECT_EQ(compareTrajectories(a, a).max_position_m, 0.0);
  EXPECT_EQ(compareTrajectories({}, b).compared, 0u);
}

}  // namespace
}  // namespace irgs
