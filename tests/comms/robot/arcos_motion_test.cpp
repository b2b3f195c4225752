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

TelemetrySample movingAt(double t, const Pose2& pose, double speed_mps) {
  TelemetrySample s = sipAt(t, pose);
  s.measured_velocity.linear_mps = speed_mps;
  return s;
}

TEST(ArcosMotion, ADriveIsOneMoveTheRobotStopsOnByItselfAtItsSpeed) {
  ArcosMotion m(testing::thesisRobot());
  m.onSample(sipAt(0.0, {}), 0.0);
  motion::DriveSpec drive;
  drive.distance_m = 0.5;
  drive.speed_mps = 0.2;
  drive.stop_at_wall = false;
  m.start({7, drive});
  const auto going = m.onSample(sipAt(0.1, {0.01, 0, 0}), 0.0);
  ASSERT_TRUE(going.has_value());
  ASSERT_TRUE(going->move_mm.has_value());
  EXPECT_EQ(*going->move_mm, 490);  // what is left from where the SIP says it is
  EXPECT_EQ(going->move_speed_mmps, 200);
  EXPECT_FALSE(going->head_deg.has_value());  // on its heading: no HEAD
  // Under way: the translational slot is left to the MOVE, nothing new is sent.
  const auto under_way = m.onSample(movingAt(1.0, {0.2, 0, 0}, 0.2), 0.0);
  ASSERT_TRUE(under_way.has_value());
  EXPECT_TRUE(under_way->moving);
  EXPECT_FALSE(under_way->move_mm.has_value());
  const auto there = m.onSample(sipAt(2.6, {0.5, 0, 0}), 0.0);
  ASSERT_TRUE(there.has_value());
  EXPECT_EQ(*there, ArcosMotionSetpoint{});  // ended: VEL 0 ends the MOVE too
  EXPECT_EQ(m.takeReports().back().kind, motion::ReportKind::kDone);
}

TEST(ArcosMotion, AMoveTheRobotDidNotRunIsSentAgainForWhatIsLeft) {
  ArcosMotion m(testing::thesisRobot());
  m.onSample(sipAt(0.0, {}), 0.0);
  motion::DriveSpec drive;
  drive.distance_m = 1.0;
  drive.stop_at_wall = false;
  m.start({3, drive});
  ASSERT_TRUE(m.onSample(sipAt(0.1, {}), 0.0)->move_mm.has_value());
  // Standing still, but not for kMoveRetry_s yet (the link is late): wait.
  EXPECT_FALSE(m.onSample(sipAt(1.5, {}), 0.0)->move_mm.has_value());
  // Moving at 2.5 s: the MOVE is running.
  EXPECT_FALSE(m.onSample(movingAt(2.5, {0.3, 0, 0}, 0.2), 0.0)->move_mm.has_value());
  // Stopped short at 0.6 m, 2 s after the MOVE: the rest is asked for.
  const auto again = m.onSample(sipAt(2.7, {0.6, 0, 0}), 0.0);
  ASSERT_TRUE(again->move_mm.has_value());
  EXPECT_EQ(*again->move_mm, 400);
}

TEST(ArcosMotion, EachLegOfSegmentsIsItsOwnMoveAfterTheTurn) {
  ArcosMotion m(testing::thesisRobot());
  m.onSample(sipAt(0.0, {}), 0.0);
  motion::SegmentsSpec legs;
  legs.points[0] = {1.0, 0.0};
  legs.points[1] = {1.0, 1.0};
  legs.count = 2;
  legs.stop_at_wall = false;
  m.start({9, legs});
  m.onSample(sipAt(0.1, {}), 0.0);  // the first turn: none needed
  const auto first = m.onSample(sipAt(0.2, {}), 0.0);
  ASSERT_TRUE(first->move_mm.has_value());
  EXPECT_EQ(*first->move_mm, 1000);
  // At the first turning point the turn comes first (HEAD, no translation), then a new MOVE.
  const auto turning = m.onSample(sipAt(6.0, {1.0, 0, 0}), 0.0);
  ASSERT_TRUE(turning.has_value());
  EXPECT_FALSE(turning->moving);
  EXPECT_EQ(turning->vel_mmps, 0);
  const auto turned = m.onSample(sipAt(8.0, {1.0, 0, degToRad(90.0)}), 0.0);
  const auto second =
      turned->move_mm ? turned : m.onSample(sipAt(8.1, {1.0, 0, degToRad(90.0)}), 0.0);
  ASSERT_TRUE(second->move_mm.has_value());
  EXPECT_EQ(*second->move_mm, 1000);
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
