#include "comms/robot/arcos_motion.hpp"

#include <gtest/gtest.h>

#include "tests/comms/robot/robot_test_support.hpp"

namespace irgs::comms {
namespace {

TelemetrySample sipAt(double t, const Pose2& pose, double rate_radps = 0.0) {
  TelemetrySample s;
  s.time_s = t;
  s.odometry_pose = pose;
  s.measured_velocity.angular_radps = rate_radps;
  return s;
}

motion::Primitive turnBy(double angle_rad, std::uint16_t id = 1) {
  motion::TurnSpec turn;
  turn.angle_rad = angle_rad;
  return {id, turn};
}

TEST(ArcosMotion, AStartBeforeAnySipIsRefusedForWantOfAnAnswer) {
  ArcosMotion m(testing::thesisRobot());
  m.start(turnBy(1.0));
  const auto reports = m.takeReports();
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].kind, motion::ReportKind::kRefused);
  EXPECT_EQ(reports[0].reason, motion::Reason::kNoAnswer);
  EXPECT_FALSE(m.running());
}

TEST(ArcosMotion, IdleSipsLeaveTheWheelsToTeleop) {
  ArcosMotion m(testing::thesisRobot());
  EXPECT_FALSE(m.onSample(sipAt(0.0, {}), 0.0).has_value());
  EXPECT_FALSE(m.onSample(sipAt(0.1, {}), 0.0).has_value());
}

TEST(ArcosMotion, AFarTurnIsAHeadingForTheRobotsOwnControllerInItsOdometryFrame) {
  ArcosMotion m(testing::thesisRobot());
  m.onSample(sipAt(0.0, {}), 0.0);
  m.start(turnBy(degToRad(90.0)));
  // The ARCOS frame is turned by -30 degrees from the map: HEAD 60.
  const auto setpoint = m.onSample(sipAt(0.1, {}), degToRad(-30.0));
  ASSERT_TRUE(setpoint.has_value());
  ASSERT_TRUE(setpoint->head_deg.has_value());
  EXPECT_EQ(*setpoint->head_deg, 60);
  EXPECT_EQ(setpoint->vel_mmps, 0);
  const auto reports = m.takeReports();
  ASSERT_FALSE(reports.empty());
  EXPECT_EQ(reports[0].kind, motion::ReportKind::kStarted);
}

TEST(ArcosMotion, NearTheHeadingTheHostNudgesWithARateAndReportsDoneWhenSettled) {
  ArcosMotion m(testing::thesisRobot());
  m.onSample(sipAt(0.0, {}), 0.0);
  m.start(turnBy(degToRad(90.0)));
  m.onSample(sipAt(0.1, {}), 0.0);
  // 3 degrees short: still the robot's own heading controller (the host's corrections are late).
  const auto close = m.onSample(sipAt(0.15, {0, 0, degToRad(87.0)}, 0.3), 0.0);
  ASSERT_TRUE(close.has_value());
  EXPECT_EQ(close->head_deg, 90);
  const auto near = m.onSample(sipAt(0.2, {0, 0, degToRad(89.0)}, 0.3), 0.0);
  ASSERT_TRUE(near.has_value());
  EXPECT_FALSE(near->head_deg.has_value());
  EXPECT_GT(near->rvel_degps, 0);
  const auto crossed = m.onSample(sipAt(0.3, {0, 0, degToRad(90.4)}, 0.0), 0.0);
  ASSERT_TRUE(crossed.has_value());
  EXPECT_EQ(*crossed, ArcosMotionSetpoint{});  // ended: stop
  EXPECT_FALSE(m.running());
  const auto reports = m.takeReports();
  ASSERT_GE(reports.size(), 2u);
  EXPECT_EQ(reports.back().kind, motion::ReportKind::kDone);
  EXPECT_DOUBLE_EQ(reports.back().time_s, 0.3);
}

TEST(ArcosMotion, ADriveSetsTheSpeedAndEndsAtItsDistance) {
  ArcosMotion m(testing::thesisRobot());
  m.onSample(sipAt(0.0, {}), 0.0);
  motion::DriveSpec drive;
  drive.distance_m = 0.5;
  drive.speed_mps = 0.2;
  drive.stop_at_wall = false;
  m.start({7, drive});
  const auto going = m.onSample(sipAt(0.1, {0.01, 0, 0}), 0.0);
  ASSERT_TRUE(going.has_value());
  EXPECT_EQ(going->vel_mmps, 200);
  EXPECT_FALSE(going->head_deg.has_value());  // on its heading: no HEAD
  const auto there = m.onSample(sipAt(2.6, {0.5, 0, 0}), 0.0);
  ASSERT_TRUE(there.has_value());
  EXPECT_EQ(there->vel_mmps, 0);
  EXPECT_EQ(m.takeReports().back().kind, motion::ReportKind::kDone);
}

TEST(ArcosMotion, ALostLinkFailsTheRunningPrimitiveAndOwesTheRobotAStop) {
  ArcosMotion m(testing::thesisRobot());
  m.onSample(sipAt(0.0, {}), 0.0);
  m.start(turnBy(1.0));
  m.abort(motion::Reason::kSafety);
  EXPECT_FALSE(m.running());
  EXPECT_TRUE(m.takeStopOwed());
  EXPECT_FALSE(m.takeStopOwed());
  const auto reports = m.takeReports();
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[1].kind, motion::ReportKind::kFailed);
  EXPECT_EQ(reports[1].reason, motion::Reason::kSafety);
}

TEST(ArcosMotion, ReportsNobodyTakesStayBounded) {
  ArcosMotion m(testing::thesisRobot());
  m.onSample(sipAt(0.0, {}), 0.0);
  for (int i = 0; i < 400; ++i)
    m.start(turnBy(1.0, static_cast<std::uint16_t>(i + 1)));  // each cancels the one before
  EXPECT_EQ(m.takeReports().size(), ArcosMotion::kMaxKeptReports);
}

TEST(ArcosMotion, HeadingArgumentsAreWholeDegreesFromZeroTo359) {
  EXPECT_EQ(arcosHeadingArgument(0.0), 0);
  EXPECT_EQ(arcosHeadingArgument(degToRad(-90.0)), 270);
  EXPECT_EQ(arcosHeadingArgument(degToRad(359.6)), 0);
  EXPECT_EQ(arcosHeadingArgument(degToRad(179.6)), 180);
}

}  // namespace
}  // namespace irgs::comms
