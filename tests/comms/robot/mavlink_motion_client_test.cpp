// The ground station's motion-primitive client, pure (comms/robot/mavlink_motion_client.hpp):
// what it sends for each start, how reports arrive, and how every lost frame is made up so the
// host never waits for ever. The robot's frames are built by hand here; the firmware's side is
// tested in tests/app/robot/firmware_motion_test.cpp and both together over a pty in
// linked_robot_motion_test.cpp.

#include "comms/robot/mavlink_motion_client.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/robot/motion_messages.hpp"
#include "comms/robot/telemetry_messages.hpp"

namespace irgs::comms {
namespace {

namespace mav = mavlink;
using motion::Reason;
using motion::ReportKind;

template <class M>
mav::Frame frameOf(const M& message) {
  mav::FrameEncoder encoder(1, 1);
  mav::FrameDecoder decoder;
  const mav::DecodeResult r = decoder.feed(encoder.encode(message).view());
  EXPECT_EQ(r.frames.size(), 1u);
  return r.frames.empty() ? mav::Frame{} : r.frames[0];
}

mav::Frame report(std::uint16_t id, ReportKind kind, double t, std::int16_t index = -1,
                  Reason reason = Reason::kNone) {
  motion::MotionReport r;
  r.id = id;
  r.kind = kind;
  r.reason = reason;
  r.time_s = t;
  r.pose = {1.0, 2.0, 0.5};
  r.distance_m = 0.25;
  r.index = index;
  return frameOf(motionReportMessage(r));
}

mav::Frame status(std::uint16_t id, mav::IrgsBehaviourState state, ReportKind last, double t,
                  std::int16_t index = -1, Reason reason = Reason::kNone,
                  motion::PrimitiveKind kind = motion::PrimitiveKind::kSegments) {
  mav::IrgsBehaviourStatus s;
  s.time_boot_ms = bootMs(t);
  s.state = static_cast<std::uint8_t>(state);
  s.progress = 1.5f;
  s.id = id;
  s.index = index;
  s.kind = static_cast<std::uint8_t>(kind);
  s.report = static_cast<std::uint8_t>(last);
  s.reason = static_cast<std::uint8_t>(reason);
  return frameOf(s);
}

CommandResult resultOf(mav::MavCmd command, CommandOutcome outcome,
                       std::optional<mav::MavResult> mav_result = std::nullopt) {
  CommandResult r;
  r.command = static_cast<std::uint16_t>(command);
  r.outcome = outcome;
  if (mav_result)
    r.mav_result = static_cast<std::uint8_t>(*mav_result);
  return r;
}

motion::Primitive turn(std::uint16_t id) {
  return {id, motion::TurnSpec{1.0, false, 0.0, 0.0}};
}

motion::Primitive segments(std::uint16_t id, int points) {
  motion::SegmentsSpec s;
  for (int i = 0; i < points; ++i)
    s.append(Vec2(0.5 * (i + 1), 0.0));
  return {id, s};
}

std::vector<ReportKind> kinds(const std::vector<motion::MotionReport>& reports) {
  std::vector<ReportKind> out;
  for (const auto& r : reports)
    out.push_back(r.kind);
  return out;
}

constexpr double kAll = 1e9;  // every sample delivered: no report waits for one

TEST(MavlinkMotionClient, TurnGoesOutAsACommandAndItsReportsArriveInOrder) {
  MavlinkMotionClient client;
  client.setTargetSystem(1);
  client.start(turn(3), 0.0);
  const MotionClientOutput out = client.takeOutput();
  ASSERT_EQ(out.commands.size(), 1u);
  EXPECT_TRUE(out.waypoints.empty());
  EXPECT_EQ(out.commands[0].primitive_id, 3);
  EXPECT_EQ(out.commands[0].command.command,
            static_cast<std::uint16_t>(mav::MavCmd::kIrgsTurnAngle));
  EXPECT_EQ(out.commands[0].command.target_system, 1);
  EXPECT_EQ(out.commands[0].command.param7, 3.0f);

  client.onFrame(report(3, ReportKind::kStarted, 10.0), 0.1);
  client.onCommandResult(3, resultOf(mav::MavCmd::kIrgsTurnAngle, CommandOutcome::kAccepted), 0.1);
  client.onFrame(report(3, ReportKind::kDone, 12.5), 2.6);
  const auto reports = client.takeReports(kAll, 2.6);
  EXPECT_EQ(kinds(reports), (std::vector<ReportKind>{ReportKind::kStarted, ReportKind::kDone}));
  EXPECT_EQ(reports[0].time_s, 10.0);  // the robot's clock
  EXPECT_EQ(reports[1].time_s, 12.5);
  EXPECT_EQ(reports[1].pose, (Pose2{1.0, 2.0, 0.5}));
  EXPECT_TRUE(client.takeOutput().empty());  // nothing resent, no status asked for
}

TEST(MavlinkMotionClient, ReportsWaitUntilTheSamplesUpToTheirTimeWereHandedOut) {
  MavlinkMotionClient client;
  client.start(turn(1), 0.0);
  client.onFrame(report(1, ReportKind::kStarted, 5.0), 0.0);
  client.onFrame(report(1, ReportKind::kDone, 6.0), 0.0);
  EXPECT_TRUE(client.takeReports(4.99, 0.1).empty());
  EXPECT_EQ(kinds(client.takeReports(5.5, 0.1)), (std::vector<ReportKind>{ReportKind::kStarted}));
  // No sample comes (telemetry switched off): the report leaves after the hold time anyway.
  EXPECT_TRUE(client.takeReports(5.5, 0.2).empty());
  EXPECT_EQ(kinds(client.takeReports(5.5, 0.31)), (std::vector<ReportKind>{ReportKind::kDone}));
}

TEST(MavlinkMotionClient, ALostFinalReportIsMadeUpFromTheStatus) {
  MavlinkMotionClient client;
  client.start(segments(8, 3), 0.0);
  client.onFrame(report(8, ReportKind::kStarted, 1.0), 0.1);
  client.onFrame(report(8, ReportKind::kTurningPoint, 2.0, 0), 1.1);
  // Turning point 1 and the final kDone are lost; the status after the end arrives.
  client.onFrame(status(8, mav::IrgsBehaviourState::kSucceeded, ReportKind::kDone, 4.0, 2), 3.1);
  const auto reports = client.takeReports(kAll, 3.1);
  ASSERT_EQ(kinds(reports),
            (std::vector<ReportKind>{ReportKind::kStarted, ReportKind::kTurningPoint,
                                     ReportKind::kTurningPoint, ReportKind::kTurningPoint,
                                     ReportKind::kDone}));
  EXPECT_EQ(reports[2].index, 1);
  EXPECT_EQ(reports[3].index, 2);
  EXPECT_EQ(reports[4].time_s, 4.0);
  EXPECT_EQ(reports[4].distance_m, 1.5);
  // The report frames arriving late change nothing: the primitive has ended.
  client.onFrame(report(8, ReportKind::kTurningPoint, 3.0, 1), 3.2);
  client.onFrame(report(8, ReportKind::kDone, 4.0), 3.2);
  EXPECT_TRUE(client.takeReports(kAll, 3.2).empty());
}

TEST(MavlinkMotionClient, ARunningStatusMakesUpAMissingStartAndTheFailureItsReason) {
  MavlinkMotionClient client;
  client.start(turn(2), 0.0);
  client.onFrame(status(2, mav::IrgsBehaviourState::kRunning, ReportKind::kStarted, 1.0, -1,
                        Reason::kNone, motion::PrimitiveKind::kTurn),
                 0.5);
  client.onFrame(status(2, mav::IrgsBehaviourState::kFailed, ReportKind::kFailed, 2.0, -1,
                        Reason::kBlocked, motion::PrimitiveKind::kTurn),
                 1.5);
  const auto reports = client.takeReports(kAll, 1.5);
  ASSERT_EQ(kinds(reports), (std::vector<ReportKind>{ReportKind::kStarted, ReportKind::kFailed}));
  EXPECT_EQ(reports[0].time_s, 1.0);
  EXPECT_EQ(reports[1].reason, Reason::kBlocked);
}

TEST(MavlinkMotionClient, AnAcceptedStartWithoutItsReportIsStartedAtTheNewestRobotTime) {
  MavlinkMotionClient client;
  client.onSample(7.25, {3.0, 4.0, 1.0});
  client.start(turn(5), 0.0);
  client.onCommandResult(5, resultOf(mav::MavCmd::kIrgsTurnAngle, CommandOutcome::kAccepted), 0.2);
  const auto reports = client.takeReports(kAll, 0.2);
  ASSERT_EQ(kinds(reports), (std::vector<ReportKind>{ReportKind::kStarted}));
  EXPECT_EQ(reports[0].time_s, 7.25);
  EXPECT_EQ(reports[0].pose, (Pose2{3.0, 4.0, 1.0}));
}

TEST(MavlinkMotionClient, ARefusalWithoutItsReportBecomesARefusedReportWithTheImpliedReason) {
  MavlinkMotionClient client;
  client.start(turn(1), 0.0);
  client.start({2, motion::DriveSpec{1.0, 0.0, true, 0.0}}, 0.0);
  client.start({3, motion::FollowWallSpec{}}, 0.0);
  client.onCommandResult(1,
                         resultOf(mav::MavCmd::kIrgsTurnAngle, CommandOutcome::kRejected,
                                  mav::MavResult::kTemporarilyRejected),
                         0.1);
  client.onCommandResult(
      2,
      resultOf(mav::MavCmd::kIrgsMoveDistance, CommandOutcome::kRejected, mav::MavResult::kDenied),
      0.1);
  client.onCommandResult(3,
                         resultOf(mav::MavCmd::kIrgsFollowWall, CommandOutcome::kRejected,
                                  mav::MavResult::kUnsupported),
                         0.1);
  const auto reports = client.takeReports(kAll, 0.1);
  ASSERT_EQ(reports.size(), 3u);
  for (const auto& r : reports)
    EXPECT_EQ(r.kind, ReportKind::kRefused);
  EXPECT_EQ(reports[0].reason, Reason::kSafety);
  EXPECT_EQ(reports[1].reason, Reason::kInvalid);
  EXPECT_EQ(reports[2].reason, Reason::kUnsupported);
}

TEST(MavlinkMotionClient, TheRobotsOwnRefusalWinsOverTheAck) {
  MavlinkMotionClient client;
  client.start(turn(1), 0.0);
  client.onFrame(report(1, ReportKind::kRefused, 1.0, -1, Reason::kSafety), 0.1);
  client.onCommandResult(
      1, resultOf(mav::MavCmd::kIrgsTurnAngle, CommandOutcome::kRejected, mav::MavResult::kDenied),
      0.1);
  const auto reports = client.takeReports(kAll, 0.1);
  ASSERT_EQ(kinds(reports), (std::vector<ReportKind>{ReportKind::kRefused}));
  EXPECT_EQ(reports[0].reason, Reason::kSafety);
}

TEST(MavlinkMotionClient, WaypointsAreResentUntilTheRobotAnswers) {
  MavlinkMotionClient client;
  client.start(segments(4, 5), 0.0);
  MotionClientOutput out = client.takeOutput();
  ASSERT_EQ(out.waypoints.size(), 1u);
  EXPECT_EQ(out.waypoints[0].id, 4);
  EXPECT_EQ(out.waypoints[0].count, 5);
  client.tick(0.49);
  EXPECT_TRUE(client.takeOutput().empty());
  client.tick(0.5);  // no answer: again
  EXPECT_EQ(client.takeOutput().waypoints.size(), 1u);
  client.onFrame(status(4, mav::IrgsBehaviourState::kRunning, ReportKind::kStarted, 1.0), 0.6);
  client.tick(1.0);
  client.tick(1.5);
  EXPECT_TRUE(client.takeOutput().empty());
  EXPECT_EQ(kinds(client.takeReports(kAll, 1.5)), (std::vector<ReportKind>{ReportKind::kStarted}));
}

TEST(MavlinkMotionClient, WaypointsNobodyAnswersEndRefusedAfterTheLastAttempt) {
  MavlinkMotionClient client;
  client.start(segments(4, 2), 0.0);
  std::size_t sent = client.takeOutput().waypoints.size();
  for (double t = 0.1; t < 3.0; t += 0.1) {
    client.tick(t);
    sent += client.takeOutput().waypoints.size();
  }
  EXPECT_EQ(sent, 4u);
  const auto reports = client.takeReports(kAll, 3.0);
  ASSERT_EQ(kinds(reports), (std::vector<ReportKind>{ReportKind::kRefused}));
  EXPECT_EQ(reports[0].reason, Reason::kNone);
}

// Primitive 1 runs on the robot (its start heard at 0.1 s), primitive 2 is sent at 1 s.
MavlinkMotionClient oneRunningAndANewerSent() {
  MavlinkMotionClient client;
  client.start(turn(1), 0.0);
  client.onFrame(report(1, ReportKind::kStarted, 1.0), 0.1);
  client.start(turn(2), 1.0);
  return client;
}

TEST(MavlinkMotionClient, ANewerPrimitiveEndsAnOlderOneWhoseFinalWasLost) {
  MavlinkMotionClient client = oneRunningAndANewerSent();
  // The robot's kCancelled of 1 is lost; 2 starts.
  client.onFrame(report(2, ReportKind::kStarted, 2.0), 1.1);
  const auto reports = client.takeReports(kAll, 1.1);
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_EQ(reports[1].id, 1);
  EXPECT_EQ(reports[1].kind, ReportKind::kCancelled);
  EXPECT_EQ(reports[2].id, 2);
  EXPECT_EQ(reports[2].kind, ReportKind::kStarted);
}

TEST(MavlinkMotionClient, AStatusOfAnotherPrimitiveEndsOursButAStaleOneDoesNotEndANewStart) {
  MavlinkMotionClient client = oneRunningAndANewerSent();
  // A status of 1 sent before 2 reached the robot: 2 stays open.
  client.onFrame(status(1, mav::IrgsBehaviourState::kRunning, ReportKind::kStarted, 1.5), 1.05);
  EXPECT_EQ(client.takeReports(kAll, 1.05).size(), 1u);
  // Another ground station's primitive (id 40000) replaced ours on the robot.
  client.onFrame(status(40000, mav::IrgsBehaviourState::kRunning, ReportKind::kStarted, 2.0), 2.0);
  const auto reports = client.takeReports(kAll, 2.0);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].id, 1);
  EXPECT_EQ(reports[0].kind, ReportKind::kCancelled);
  // 2 was never heard of: still waiting for its command result.
  client.onCommandResult(2, resultOf(mav::MavCmd::kIrgsTurnAngle, CommandOutcome::kTimedOut), 3.0);
  const auto timed_out = client.takeReports(kAll, 3.0);
  ASSERT_EQ(timed_out.size(), 1u);
  EXPECT_EQ(timed_out[0].id, 2);
  EXPECT_EQ(timed_out[0].kind, ReportKind::kRefused);
}

TEST(MavlinkMotionClient, ReportsOfPrimitivesStartedElsewhereAreNotDelivered) {
  MavlinkMotionClient client;
  client.onFrame(report(33000, ReportKind::kStarted, 1.0), 0.0);
  client.onFrame(report(33000, ReportKind::kDone, 2.0), 0.0);
  client.onFrame(status(33000, mav::IrgsBehaviourState::kSucceeded, ReportKind::kDone, 2.0), 0.0);
  EXPECT_TRUE(client.takeReports(kAll, 0.0).empty());
}

TEST(MavlinkMotionClient, LinkLossFailsTheOpenPrimitiveAndStopsItIfTheRobotStillRunsIt) {
  MavlinkMotionClient client;
  client.onSample(3.0, {1.0, 1.0, 0.0});
  client.start({6, motion::FollowWallSpec{}}, 0.0);
  client.onFrame(report(6, ReportKind::kStarted, 3.0), 0.1);
  client.takeOutput();
  client.onLinkLost(2.0);
  const auto reports = client.takeReports(kAll, 2.0);
  ASSERT_EQ(kinds(reports), (std::vector<ReportKind>{ReportKind::kStarted, ReportKind::kFailed}));
  EXPECT_EQ(reports[1].reason, Reason::kSafety);
  // Only our heartbeats were lost on the way back: the robot still follows the wall.
  client.onFrame(status(6, mav::IrgsBehaviourState::kRunning, ReportKind::kStarted, 5.0), 2.5);
  const MotionClientOutput out = client.takeOutput();
  ASSERT_EQ(out.commands.size(), 1u);
  EXPECT_EQ(out.commands[0].command.command, static_cast<std::uint16_t>(mav::MavCmd::kIrgsStop));
  EXPECT_EQ(out.commands[0].command.param7, 6.0f);
  EXPECT_TRUE(client.takeReports(kAll, 2.5).empty());  // no second final
}

TEST(MavlinkMotionClient, ARunningPrimitiveHeardOfNoMoreMakesItAskForTheStatus) {
  MavlinkMotionClient client;
  client.start(segments(9, 2), 0.0);
  client.onFrame(report(9, ReportKind::kStarted, 1.0), 0.1);
  client.takeOutput();
  client.tick(3.0);
  EXPECT_TRUE(client.takeOutput().empty());
  client.tick(3.1);  // 3 s since the last word
  MotionClientOutput out = client.takeOutput();
  ASSERT_EQ(out.commands.size(), 1u);
  EXPECT_EQ(out.commands[0].command.command,
            static_cast<std::uint16_t>(mav::MavCmd::kRequestMessage));
  EXPECT_EQ(out.commands[0].command.param1, static_cast<float>(mav::IrgsBehaviourStatus::kId));
  client.tick(4.0);
  EXPECT_TRUE(client.takeOutput().empty());  // once per timeout, not every tick
  client.onFrame(status(9, mav::IrgsBehaviourState::kSucceeded, ReportKind::kDone, 5.0, 1), 4.2);
  EXPECT_EQ(kinds(client.takeReports(kAll, 4.2)).back(), ReportKind::kDone);
  client.tick(10.0);
  EXPECT_TRUE(client.takeOutput().empty());
}

TEST(MavlinkMotionClient, CancelStopsTheNewestOpenPrimitiveByItsId) {
  MavlinkMotionClient client;
  client.start(turn(1), 0.0);
  client.onFrame(report(1, ReportKind::kStarted, 1.0), 0.1);
  client.takeOutput();
  client.cancel(0.2);
  MotionClientOutput out = client.takeOutput();
  ASSERT_EQ(out.commands.size(), 1u);
  EXPECT_EQ(out.commands[0].command.command, static_cast<std::uint16_t>(mav::MavCmd::kIrgsStop));
  EXPECT_EQ(out.commands[0].command.param7, 1.0f);
  // The kCancelled frame is lost; the robot acknowledged the stop after sending it.
  client.onCommandResult(1, resultOf(mav::MavCmd::kIrgsStop, CommandOutcome::kAccepted), 0.3);
  EXPECT_EQ(kinds(client.takeReports(kAll, 0.3)),
            (std::vector<ReportKind>{ReportKind::kStarted, ReportKind::kCancelled}));
  client.cancel(0.4);
  EXPECT_TRUE(client.takeOutput().empty());  // nothing open: nothing to stop
}

TEST(MavlinkMotionClient, ASpecThatCannotBeEncodedOrIdZeroIsRefusedAtOnce) {
  MavlinkMotionClient client;
  motion::SegmentsSpec far;
  far.append(Vec2(0.0, 0.0));
  far.append(Vec2(500.0, 0.0));
  client.start({1, far}, 0.0);
  client.start({0, motion::TurnSpec{}}, 0.0);
  EXPECT_TRUE(client.takeOutput().empty());
  const auto reports = client.takeReports(kAll, 0.0);
  ASSERT_EQ(kinds(reports), (std::vector<ReportKind>{ReportKind::kRefused, ReportKind::kRefused}));
  EXPECT_EQ(reports[0].reason, Reason::kInvalid);
}

}  // namespace
}  // namespace irgs::comms
