#include "core/mapping/sonar_mapper.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace irgs {
namespace {

// Two sonars: one looking ahead from the front, one looking left from the left side.
RobotProfile twoSonarRobot() {
  RobotProfile p;
  p.name = "test";
  SonarSpec front;
  front.name = "front";
  front.mount = {0.1, 0.0, 0.0};
  front.beam_width_rad = degToRad(25.0);
  front.max_range_m = 4.0;
  SonarSpec left;
  left.name = "left";
  left.mount = {0.0, 0.1, kPi / 2.0};
  left.beam_width_rad = degToRad(25.0);
  left.max_range_m = 3.0;
  p.sonars = {front, left};
  return p;
}

TelemetrySample sampleAt(const Pose2& odometry, std::vector<SonarReading> readings) {
  TelemetrySample s;
  s.odometry_pose = odometry;
  s.true_pose = Pose2{odometry.x + 0.5, odometry.y - 0.5, odometry.theta + 0.3};  // ignored
  s.sonar = std::move(readings);
  return s;
}

TEST(SonarMapper, PlacesConesAtTheMountOnTheOdometryPose) {
  const SonarMapper mapper(twoSonarRobot());
  OccupancyGrid grid(0.01);
  // Robot at (1, 2) facing +y: the front sonar sits at (1, 2.1) looking +y, the left one at
  // (0.9, 2) looking -x.
  const Pose2 pose{1.0, 2.0, kPi / 2.0};
  const SonarMapStats stats =
      mapper.integrate(sampleAt(pose, {{0, 1.0, true}, {1, 0.5, true}}), grid);
  EXPECT_EQ(stats.integrated, 2);
  EXPECT_EQ(stats.skipped, 0);
  EXPECT_GT(grid.logOdds(grid.cellAt({1.0, 3.1})), 0.0f);  // front echo
  EXPECT_LT(grid.logOdds(grid.cellAt({1.0, 2.6})), 0.0f);
  EXPECT_GT(grid.logOdds(grid.cellAt({0.4, 2.0})), 0.0f);  // left echo
  EXPECT_LT(grid.logOdds(grid.cellAt({0.7, 2.0})), 0.0f);
  // Exactly what the two cones give when placed by hand.
  OccupancyGrid expected(0.01);
  expected.integrateSonar({1.0, 2.1}, kPi / 2.0, degToRad(25.0), 1.0, true, mapper.model());
  expected.integrateSonar({0.9, 2.0}, kPi, degToRad(25.0), 0.5, true, mapper.model());
  EXPECT_TRUE(grid == expected);
}

TEST(SonarMapper, EchoBeyondTheValidDistanceCountsAsNoEchoUpToIt) {
  SonarInverseModel model;
  model.no_echo_free_range_m = 10.0;  // let the valid distance be the limit
  const SonarMapper mapper(twoSonarRobot(), model, 1.2);
  EXPECT_DOUBLE_EQ(mapper.validDistance_m(0), 1.2);
  OccupancyGrid grid(0.01);
  mapper.integrate(sampleAt({0.0, 0.0, 0.0}, {{0, 2.0, true}}), grid);
  EXPECT_FALSE(grid.observed(grid.cellAt({2.1, 0.0})));     // no arc at the reported range
  EXPECT_LT(grid.logOdds(grid.cellAt({1.25, 0.0})), 0.0f);  // free up to 0.1 + 1.2 m
  EXPECT_FALSE(grid.observed(grid.cellAt({1.35, 0.0})));
  const Box2 b = grid.observedBounds();
  for (int row = grid.cellAt(b.min).row; row < grid.cellAt(b.max).row; ++row)
    for (int col = grid.cellAt(b.min).col; col < grid.cellAt(b.max).col; ++col)
      ASSERT_LE(grid.logOdds({col, row}), 0.0f);
}

TEST(SonarMapper, NoEchoClearsUpToTheSmallerOfValidDistanceAndModelRange) {
  SonarInverseModel model;
  model.no_echo_free_range_m = 0.8;
  const SonarMapper mapper(twoSonarRobot(), model);  // valid distance = max range (4 m, 3 m)
  EXPECT_DOUBLE_EQ(mapper.validDistance_m(0), 4.0);
  EXPECT_DOUBLE_EQ(mapper.validDistance_m(1), 3.0);
  OccupancyGrid grid(0.01);
  mapper.integrate(sampleAt({0.0, 0.0, 0.0}, {{0, 0.0, false}}), grid);
  EXPECT_LT(grid.logOdds(grid.cellAt({0.85, 0.0})), 0.0f);
  EXPECT_FALSE(grid.observed(grid.cellAt({0.95, 0.0})));
}

TEST(SonarMapper, ValidDistanceAboveMaxRangeIsCappedPerSensor) {
  const SonarMapper mapper(twoSonarRobot(), {}, 3.5);
  EXPECT_DOUBLE_EQ(mapper.validDistance_m(0), 3.5);
  EXPECT_DOUBLE_EQ(mapper.validDistance_m(1), 3.0);
}

TEST(SonarMapper, SkipsUnusableReadingsAndCountsThem) {
  const SonarMapper mapper(twoSonarRobot());
  OccupancyGrid grid(0.01);
  const SonarMapStats stats = mapper.integrate(
      sampleAt({0.0, 0.0, 0.0}, {{-1, 1.0, true},
                                 {2, 1.0, true},
                                 {0, std::nan(""), true},
                                 {0, -0.5, true},
                                 {1, std::nan(""), false},  // range unused without echo
                                 {0, 1.0, true}}),
      grid);
  EXPECT_EQ(stats.integrated, 2);
  EXPECT_EQ(stats.skipped, 4);
  const SonarMapStats bad_pose =
      mapper.integrate(sampleAt({std::nan(""), 0.0, 0.0}, {{0, 1.0, true}}), grid);
  EXPECT_EQ(bad_pose.skipped, 1);
  const SonarMapStats far_away =
      mapper.integrate(sampleAt({1e8, 0.0, 0.0}, {{0, 1.0, true}}), grid);
  EXPECT_EQ(far_away.skipped, 1);
}

TEST(SonarMapper, RejectsInvalidProfilesAndSettings) {
  RobotProfile wide = twoSonarRobot();
  wide.sonars[1].beam_width_rad = kPi;
  EXPECT_THROW(SonarMapper{wide}, std::invalid_argument);
  RobotProfile no_range = twoSonarRobot();
  no_range.sonars[0].max_range_m = 0.0;
  EXPECT_THROW(SonarMapper{no_range}, std::invalid_argument);
  RobotProfile bad_mount = twoSonarRobot();
  bad_mount.sonars[0].mount.theta = std::nan("");
  EXPECT_THROW(SonarMapper{bad_mount}, std::invalid_argument);
  EXPECT_THROW(SonarMapper(twoSonarRobot(), {}, 0.0), std::invalid_argument);
  SonarInverseModel bad_model;
  bad_model.arc_thickness_m = -1.0;
  EXPECT_THROW(SonarMapper(twoSonarRobot(), bad_model), std::invalid_argument);
  EXPECT_NO_THROW(SonarMapper(RobotProfile{}));  // no sonars: nothing to map, not an error
}

}  // namespace
}  // namespace irgs
