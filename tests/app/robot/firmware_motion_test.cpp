// The motion primitives on the virtual firmware, from dialect bytes (docs/protocol.md section
// 17): each kind runs through FirmwareCore's one MotionExecutor and reports in order; starts
// are idempotent; stops by id; the safety rules end a running primitive; a mission longer than
// 32 legs runs in chunks; and, with the ground station's pure client on the other end of a
// lossy byte pipe, every lost report is made up. Fake clock, no sleeps.

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <vector>

#include "comms/link/command_manager.hpp"
#include "comms/robot/mavlink_motion_client.hpp"
#include "comms/robot/motion_messages.hpp"
#include "tests/app/robot/firmware_test_support.hpp"

namespace irgs::app {
namespace {

using namespace firmware_test;
using motion::Reason;
using motion::ReportKind;

constexpr auto kAccepted = static_cast<std::uint8_t>(mav::MavResult::kAccepted);
constexpr auto kDenied = static_cast<std::uint8_t>(mav::MavResult::kDenied);

// The firmware and a ground station whose heartbeat it has heard for 0.1 s.
struct Rig {
  explicit Rig(FirmwareCore firmware) : core(std::move(firmware)), gcs(core) {
    gcs.run(0.1, true, std::nullopt);
  }
  explicit Rig(WorldMap map, FirmwareConfig config = {}) : Rig(makeCore(std::move(map), config)) {}
  FirmwareCore core;
  Gcs gcs;
};

// Sends a primitive as the ground station would (COMMAND_LONG or IRGS_WAYPOINTS).
void sendPrimitive(Gcs& gcs, const motion::Primitive& p, std::uint8_t confirmation = 0) {
  comms::EncodedPrimitive e = comms::encodePrimitive(p, 1);
  ASSERT_TRUE(e.error.empty()) << e.error;
  if (e.command) {
    e.command->confirmation = confirmation;
    gcs.send(*e.command, gcs.now());
  } else {
    gcs.send(*e.waypoints, gcs.now());
  }
}

std::vector<motion::MotionReport> reportsOf(const Gcs& gcs, std::uint16_t id) {
  std::vector<motion::MotionReport> out;
  for (const auto& m : gcs.all<mav::IrgsMotionReport>())
    if (const auto r = comms::motionReportFrom(m); r && r->id == id)
      out.push_back(*r);
  return out;
}

std::vector<ReportKind> kindsOf(const std::vector<motion::MotionReport>& reports) {
  std::vector<ReportKind> out;
  for (const auto& r : reports)
    out.push_back(r.kind);
  return out;
}

// kStarted first, exactly one final report and it last, times never going back.
void expectWellFormed(const std::vector<motion::MotionReport>& reports) {
  ASSERT_FALSE(reports.empty());
  EXPECT_EQ(reports.front().kind, ReportKind::kStarted);
  EXPECT_TRUE(motion::isFinal(reports.back().kind));
  EXPECT_EQ(std::count_if(reports.begin(), reports.end(),
                          [](const auto& r) { return motion::isFinal(r.kind); }),
            1);
  for (std::size_t i = 1; i < reports.size(); ++i)
    EXPECT_GE(reports[i].time_s, reports[i - 1].time_s);
}

std::vector<mav::IrgsBehaviourStatus> statusesOf(const Gcs& gcs, std::uint16_t id) {
  std::vector<mav::IrgsBehaviourStatus> out;
  for (const auto& s : gcs.all<mav::IrgsBehaviourStatus>())
    if (s.id == id)
      out.push_back(s);
  return out;
}

// ---- Each kind from dialect bytes --------------------------------------------------------------

TEST(FirmwareMotion, TurnsByAnAngleAndToAHeadingInQuanta) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  sendPrimitive(gcs, {11, motion::TurnSpec{kPi / 2.0, false, 0.0, 0.0}});
  gcs.run(5.0, true, std::nullopt);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 11)), (std::vector{ReportKind::kStarted, ReportKind::kDone}));
  EXPECT_NEAR(core.simulator().odometryPose().theta, kPi / 2.0, degToRad(1.0));
  // To the heading -50 deg in 15 deg quanta: -45 deg.
  sendPrimitive(gcs, {12, motion::TurnSpec{degToRad(-50.0), true, degToRad(15.0), 0.0}});
  gcs.run(12.0, true, std::nullopt);
  const auto reports = reportsOf(gcs, 12);
  expectWellFormed(reports);
  EXPECT_EQ(reports.back().kind, ReportKind::kDone);
  EXPECT_NEAR(core.simulator().odometryPose().theta, degToRad(-45.0), degToRad(1.0));
  EXPECT_NEAR(reports.back().distance_m, degToRad(135.0), degToRad(1.5));
  ASSERT_EQ(acksFor(gcs, mav::MavCmd::kIrgsTurnAngle).size(), 2u);
  EXPECT_EQ(acksFor(gcs, mav::MavCmd::kIrgsTurnAngle)[1].result, kAccepted);
  const auto status = statusesOf(gcs, 12);
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status.back().state, kSucceeded);
  EXPECT_EQ(status.back().kind, static_cast<std::uint8_t>(mav::IrgsPrimitiveKind::kTurn));
  EXPECT_EQ(status.back().report, static_cast<std::uint8_t>(mav::IrgsMotionReportKind::kDone));
  EXPECT_NEAR(status.back().progress, -degToRad(135.0), degToRad(1.5));  // clockwise
}

TEST(FirmwareMotion, DrivesADistanceAndStopsShortOfAWallAhead) {
  Rig rig(room(true));  // a wall 0.4 m ahead
  auto& [core, gcs] = rig;
  sendPrimitive(gcs, {21, motion::DriveSpec{-0.3, 0.2, true, 0.0}});  // backwards: no wall
  gcs.run(4.0, true, std::nullopt);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 21)), (std::vector{ReportKind::kStarted, ReportKind::kDone}));
  EXPECT_NEAR(core.simulator().odometryPose().x, -0.3, 0.015);
  sendPrimitive(gcs, {22, motion::DriveSpec{2.0, 0.2, true, 0.0}});
  gcs.run(10.0, true, std::nullopt);
  const auto reports = reportsOf(gcs, 22);
  expectWellFormed(reports);
  EXPECT_EQ(reports.back().kind, ReportKind::kFrontWall);
  EXPECT_TRUE(stopped(core));
  EXPECT_LT(core.simulator().truePose().x, 0.4 - 0.15);  // the body never touched it
  EXPECT_EQ(core.safety().bumpers, 0u);
}

TEST(FirmwareMotion, FollowsAWallWithDistanceMarksUntilTheTravelLimit) {
  Rig rig(room(false, Pose2{-2.0, -2.7, 0.0}));  // south wall on the right
  auto& [core, gcs] = rig;
  motion::FollowWallSpec spec;
  spec.wall_on_left = false;
  spec.distance_m = 0.3;
  spec.speed_mps = 0.2;
  spec.travel_limit_m = 0.9;
  spec.report_every_m = 0.25;
  sendPrimitive(gcs, {31, spec});
  gcs.run(10.0, true, std::nullopt);
  const auto reports = reportsOf(gcs, 31);
  expectWellFormed(reports);
  EXPECT_EQ(reports.back().kind, ReportKind::kDone);
  std::vector<double> marks;
  for (const auto& r : reports)
    if (r.kind == ReportKind::kDistanceMark)
      marks.push_back(r.distance_m);
  ASSERT_EQ(marks.size(), 3u);
  for (std::size_t i = 0; i < marks.size(); ++i)
    EXPECT_NEAR(marks[i], 0.25 * static_cast<double>(i + 1), 0.02) << i;
  EXPECT_NEAR(reports.back().distance_m, 0.9, 0.02);
  EXPECT_NEAR(core.simulator().truePose().y, -2.7, 0.05);
  EXPECT_TRUE(stopped(core));
}

TEST(FirmwareMotion, RunsWaypointSegmentsReportingEachTurningPoint) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  motion::SegmentsSpec spec;
  spec.append(Vec2(0.6, 0.0));
  spec.append(Vec2(0.6, 0.6));
  spec.append(Vec2(0.0, 0.6));
  sendPrimitive(gcs, {41, spec});
  gcs.run(30.0, true, std::nullopt);
  const auto reports = reportsOf(gcs, 41);
  expectWellFormed(reports);
  ASSERT_EQ(kindsOf(reports),
            (std::vector{ReportKind::kStarted, ReportKind::kTurningPoint, ReportKind::kTurningPoint,
                         ReportKind::kTurningPoint, ReportKind::kDone}));
  for (int i = 0; i < 3; ++i) {
    const auto& r = reports[static_cast<std::size_t>(i + 1)];
    EXPECT_EQ(r.index, i);
    EXPECT_NEAR((r.pose.position() - spec.points[static_cast<std::size_t>(i)]).norm(), 0.0, 0.02);
  }
  EXPECT_NEAR(reports.back().distance_m, 1.8, 0.03);
  EXPECT_TRUE(gcs.all<mav::CommandAck>().empty());  // IRGS_WAYPOINTS is answered by reports
  EXPECT_EQ(statusesOf(gcs, 41).back().index, 2);
  EXPECT_EQ(statusesOf(gcs, 41).back().command, 0);
}

TEST(FirmwareMotion, FollowsAPathThroughItsVertices) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  motion::FollowPathSpec spec;
  spec.append(Vec2(0.8, 0.0));
  spec.append(Vec2(1.4, 0.5));
  spec.speed_mps = 0.2;
  sendPrimitive(gcs, {51, spec});
  gcs.run(20.0, true, std::nullopt);
  const auto reports = reportsOf(gcs, 51);
  expectWellFormed(reports);
  EXPECT_EQ(kindsOf(reports), (std::vector{ReportKind::kStarted, ReportKind::kTurningPoint,
                                           ReportKind::kTurningPoint, ReportKind::kDone}));
  // The end of the last piece along it (the path law still converges sideways: paper 004's
  // follower is tested on its own in tests/core/motion).
  const Vec2 end = core.simulator().odometryPose().position();
  const Vec2 piece = Vec2(1.4, 0.5) - Vec2(0.8, 0.0);
  EXPECT_NEAR((end - Vec2(0.8, 0.0)).dot(piece.normalized()), piece.norm(), 0.02);
  EXPECT_LT((end - Vec2(1.4, 0.5)).norm(), 0.15);
}

// ---- Idempotent starts, stops by id ------------------------------------------------------------

TEST(FirmwareMotion, ARetriedCommandWithTheSameIdIsAcknowledgedAgainNotRestarted) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  const motion::Primitive drive{61, motion::DriveSpec{0.6, 0.2, false, 0.0}};
  sendPrimitive(gcs, drive);
  gcs.run(1.5, true, std::nullopt);
  sendPrimitive(gcs, drive, 1);  // its ack was lost: the ground station retries
  gcs.run(8.0, true, std::nullopt);
  const auto move_acks = acksFor(gcs, mav::MavCmd::kIrgsMoveDistance);
  ASSERT_EQ(move_acks.size(), 2u);
  EXPECT_EQ(move_acks[0].result, kAccepted);
  EXPECT_EQ(move_acks[1].result, kAccepted);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 61)), (std::vector{ReportKind::kStarted, ReportKind::kDone}));
  EXPECT_NEAR(core.simulator().odometryPose().x, 0.6, 0.015);  // 0.6 m once, not 0.6 m more

  // A refused start is refused again on its retry, with the same answer.
  sendPrimitive(gcs, {62, motion::DriveSpec{std::nan(""), 0.0, false, 0.0}});
  sendPrimitive(gcs, {62, motion::DriveSpec{std::nan(""), 0.0, false, 0.0}}, 1);
  gcs.run(8.5, true, std::nullopt);
  const auto refused = acksFor(gcs, mav::MavCmd::kIrgsMoveDistance);
  ASSERT_EQ(refused.size(), 4u);
  EXPECT_EQ(refused[2].result, kDenied);
  EXPECT_EQ(refused[3].result, kDenied);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 62)), (std::vector{ReportKind::kRefused}));
  EXPECT_EQ(reportsOf(gcs, 62)[0].reason, Reason::kInvalid);
}

TEST(FirmwareMotion, ALateRetryOfAnOlderPrimitiveDoesNotReplaceTheNewerOne) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  sendPrimitive(gcs, {71, motion::TurnSpec{1.0, false, 0.0, 0.0}});
  gcs.run(0.3, true, std::nullopt);
  sendPrimitive(gcs, {72, motion::DriveSpec{0.4, 0.2, false, 0.0}});
  gcs.run(0.6, true, std::nullopt);
  sendPrimitive(gcs, {71, motion::TurnSpec{1.0, false, 0.0, 0.0}}, 2);  // the turn's late retry
  gcs.run(6.0, true, std::nullopt);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 71)),
            (std::vector{ReportKind::kStarted, ReportKind::kCancelled}));
  EXPECT_EQ(kindsOf(reportsOf(gcs, 72)), (std::vector{ReportKind::kStarted, ReportKind::kDone}));
  EXPECT_EQ(acksFor(gcs, mav::MavCmd::kIrgsTurnAngle).back().result, kAccepted);
}

TEST(FirmwareMotion, RepeatedWaypointsAreAnsweredWithTheStatusNotStartedAgain) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  motion::SegmentsSpec spec;
  spec.append(Vec2(0.5, 0.0));
  sendPrimitive(gcs, {81, spec});
  gcs.run(0.2, true, std::nullopt);
  const std::size_t statuses = statusesOf(gcs, 81).size();
  sendPrimitive(gcs, {81, spec});  // the resend crossed the robot's answer
  gcs.run(0.21, true, std::nullopt);
  EXPECT_EQ(statusesOf(gcs, 81).size(), statuses + 1);
  EXPECT_EQ(statusesOf(gcs, 81).back().state, kRunning);
  gcs.run(8.0, true, std::nullopt);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 81)),
            (std::vector{ReportKind::kStarted, ReportKind::kTurningPoint, ReportKind::kDone}));
}

TEST(FirmwareMotion, AStopWithAnIdStopsOnlyThatPrimitive) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  sendPrimitive(gcs, {91, motion::DriveSpec{0.2, 0.2, false, 0.0}});
  gcs.run(3.0, true, std::nullopt);
  sendPrimitive(gcs, {92, motion::DriveSpec{1.0, 0.2, false, 0.0}});
  gcs.run(3.5, true, std::nullopt);
  gcs.send(comms::stopPrimitiveCommand(91, 1), gcs.now());  // stale: 91 ended long ago
  gcs.run(4.0, true, std::nullopt);
  EXPECT_FALSE(stopped(core));
  EXPECT_EQ(kindsOf(reportsOf(gcs, 92)), (std::vector{ReportKind::kStarted}));
  gcs.send(comms::stopPrimitiveCommand(92, 1), gcs.now());
  gcs.run(5.0, true, std::nullopt);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 92)),
            (std::vector{ReportKind::kStarted, ReportKind::kCancelled}));
  EXPECT_TRUE(stopped(core));
  EXPECT_EQ(statusesOf(gcs, 92).back().state, kAborted);
  // A stop overtaking its start (the start was lost and is retried): the start never runs.
  gcs.send(comms::stopPrimitiveCommand(93, 1), gcs.now());
  sendPrimitive(gcs, {93, motion::TurnSpec{1.0, false, 0.0, 0.0}}, 1);
  gcs.run(6.0, true, std::nullopt);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 93)), (std::vector{ReportKind::kCancelled}));
  EXPECT_EQ(acksFor(gcs, mav::MavCmd::kIrgsTurnAngle).back().result, kDenied);
  EXPECT_TRUE(stopped(core));
  for (const auto& a : acksFor(gcs, mav::MavCmd::kIrgsStop))
    EXPECT_EQ(a.result, kAccepted);
}

// ---- Safety rules end a running primitive ------------------------------------------------------

TEST(FirmwareMotion, GroundStationSilenceFailsThePrimitiveWithSafety) {
  Rig rig(room(false, Pose2{-2.0, -2.7, 0.0}));  // the only heartbeat: 0.01 s
  auto& [core, gcs] = rig;
  sendPrimitive(gcs, {101, motion::FollowWallSpec{false, 0.3, 0.2, 0.0, false, false, 0.0}});
  gcs.run(3.0, false, std::nullopt);
  const auto reports = reportsOf(gcs, 101);
  expectWellFormed(reports);
  EXPECT_EQ(reports.back().kind, ReportKind::kFailed);
  EXPECT_EQ(reports.back().reason, Reason::kSafety);
  EXPECT_NEAR(reports.back().time_s, 0.01 + 1.5, 0.03);
  EXPECT_EQ(statusesOf(gcs, 101).back().state, kAborted);
  EXPECT_TRUE(stopped(core));
}

TEST(FirmwareMotion, EmergencyStopFailsThePrimitiveAndRefusesTheNextWithSafety) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  sendPrimitive(gcs, {111, motion::DriveSpec{1.0, 0.2, false, 0.0}});
  gcs.run(1.0, true, std::nullopt);
  gcs.command(mav::MavCmd::kIrgsEmergencyStop, 1.0f, gcs.now());
  sendPrimitive(gcs, {112, motion::TurnSpec{1.0, false, 0.0, 0.0}});
  gcs.run(2.0, true, std::nullopt);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 111)), (std::vector{ReportKind::kStarted, ReportKind::kFailed}));
  EXPECT_EQ(reportsOf(gcs, 111).back().reason, Reason::kSafety);
  ASSERT_EQ(kindsOf(reportsOf(gcs, 112)), (std::vector{ReportKind::kRefused}));
  EXPECT_EQ(reportsOf(gcs, 112)[0].reason, Reason::kSafety);
  EXPECT_EQ(acksFor(gcs, mav::MavCmd::kIrgsTurnAngle).back().result, kDenied);
  EXPECT_TRUE(stopped(core));
}

TEST(FirmwareMotion, TheOperatorsTeleopAndAPlainStopCancelThePrimitive) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  sendPrimitive(gcs, {121, motion::TurnSpec{3.0, false, 0.0, 0.0}});
  gcs.run(0.5, true, std::nullopt);
  gcs.manual(0, 500, gcs.now());  // the operator turns the robot himself
  gcs.run(0.6, true, std::nullopt);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 121)),
            (std::vector{ReportKind::kStarted, ReportKind::kCancelled}));
  gcs.run(1.5, true, std::nullopt);
  sendPrimitive(gcs, {122, motion::DriveSpec{1.0, 0.2, false, 0.0}});
  gcs.run(2.0, true, std::nullopt);
  gcs.command(mav::MavCmd::kIrgsStop, 0.0f, gcs.now());
  gcs.run(3.5, true, std::nullopt);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 122)),
            (std::vector{ReportKind::kStarted, ReportKind::kCancelled}));
  EXPECT_TRUE(stopped(core));
}

TEST(FirmwareMotion, ABumperStopsTheWheelsAtOnceAndEndsADriveAsBumped) {
  Rig rig(room(true));  // a wall 0.4 m ahead, the sonar stop off
  auto& [core, gcs] = rig;
  sendPrimitive(gcs, {131, motion::DriveSpec{1.0, 0.2, false, 0.0}});
  gcs.run(6.0, true, std::nullopt);
  const auto reports = reportsOf(gcs, 131);
  expectWellFormed(reports);
  EXPECT_EQ(reports.back().kind, ReportKind::kFailed);
  EXPECT_EQ(reports.back().reason, Reason::kBumped);
  EXPECT_TRUE(stopped(core));
  EXPECT_TRUE(gcs.saidSomething("bumper"));
  // Toward the pressed bumper nothing starts; away from it a drive does.
  sendPrimitive(gcs, {132, motion::DriveSpec{0.3, 0.2, false, 0.0}});
  sendPrimitive(gcs, {133, motion::DriveSpec{-0.2, 0.2, false, 0.0}});
  gcs.run(9.0, true, std::nullopt);
  ASSERT_EQ(kindsOf(reportsOf(gcs, 132)), (std::vector{ReportKind::kRefused}));
  EXPECT_EQ(reportsOf(gcs, 132)[0].reason, Reason::kBumped);
  EXPECT_EQ(kindsOf(reportsOf(gcs, 133)), (std::vector{ReportKind::kStarted, ReportKind::kDone}));
}

TEST(FirmwareMotion, WaypointsBlockedWithoutBumperContactEndOnTheDrivesStallReport) {
  // No bumpers, the sonar stop off: the simulator holds the body at the wall and the drive
  // reports its wheels stalled, which ends the run as contact long before the no-progress
  // watchdog would (that one: MotionExecutor.WaypointsThatMakeNoProgressWithoutAnyContact...).
  Rig rig(makeBumperlessCore(room(true)));
  auto& [core, gcs] = rig;
  motion::SegmentsSpec spec;
  spec.append(Vec2(1.0, 0.0));
  spec.stop_at_wall = false;
  sendPrimitive(gcs, {141, spec});
  gcs.run(15.0, true, std::nullopt);
  const auto reports = reportsOf(gcs, 141);
  expectWellFormed(reports);
  EXPECT_EQ(reports.back().kind, ReportKind::kFailed);
  EXPECT_EQ(reports.back().reason, Reason::kBumped);
  EXPECT_TRUE(stopped(core));
  EXPECT_TRUE(gcs.saidSomething("segments failed: bumped"));
}

// ---- Status on request, compact rate, long missions ---------------------------------------------

TEST(FirmwareMotion, RequestMessageAnswersWithTheStatusOfTheLastPrimitive) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  sendPrimitive(gcs, {151, motion::TurnSpec{0.5, false, 0.0, 0.0}});
  gcs.run(4.0, true, std::nullopt);
  const std::size_t before = statusesOf(gcs, 151).size();
  gcs.command(mav::MavCmd::kRequestMessage, static_cast<float>(mav::IrgsBehaviourStatus::kId),
              gcs.now());
  gcs.run(4.1, true, std::nullopt);
  ASSERT_EQ(statusesOf(gcs, 151).size(), before + 1);
  EXPECT_EQ(statusesOf(gcs, 151).back().state, kSucceeded);
  EXPECT_EQ(acksFor(gcs, mav::MavCmd::kRequestMessage).back().result, kAccepted);
  gcs.command(mav::MavCmd::kRequestMessage, static_cast<float>(mav::Heartbeat::kId), gcs.now());
  gcs.run(4.2, true, std::nullopt);
  EXPECT_EQ(acksFor(gcs, mav::MavCmd::kRequestMessage).back().result,
            static_cast<std::uint8_t>(mav::MavResult::kUnsupported));
}

TEST(FirmwareMotion, StatusComesEveryHalfSecondWhileRunningAndEveryTwoSecondsOnA9600Link) {
  for (const bool slow : {false, true}) {
    SCOPED_TRACE(slow ? "9600" : "115200");
    Rig rig(room(false), slow ? slowLinkFirmwareConfig() : FirmwareConfig{});
    auto& [core, gcs] = rig;
    sendPrimitive(gcs, {161, motion::TurnSpec{100.0, false, 0.0, 0.2}});  // runs for minutes
    gcs.run(10.1, true, std::nullopt);
    const auto statuses = statusesOf(gcs, 161);
    EXPECT_NEAR(static_cast<double>(statuses.size()), slow ? 5.0 + 1.0 : 20.0 + 1.0, 1.0);
  }
}

TEST(FirmwareMotion, AMissionOfMoreThan32LegsRunsInChunksUnderOneId) {
  Rig rig(room(false));
  auto& [core, gcs] = rig;
  // 40 waypoints on a zigzag: 40 legs (no two collinear), 6.7 cm each.
  std::vector<Vec2> path;
  for (int i = 0; i < 40; ++i)
    path.emplace_back(0.06 * (i + 1), i % 2 == 0 ? 0.03 : 0.0);
  mav::MissionCount count;
  count.target_system = 1;
  count.count = static_cast<std::uint16_t>(path.size());
  gcs.send(count, gcs.now());
  std::size_t seen = 0;
  while (gcs.all<mav::MissionAck>().empty() && gcs.now() < 20.0) {
    gcs.run(gcs.now() + 0.01, true, std::nullopt);
    for (; seen < gcs.received.size(); ++seen) {
      if (const auto request = gcs.received[seen].frame.as<mav::MissionRequestInt>()) {
        mav::MissionItemInt item;
        item.target_system = 1;
        item.seq = request->seq;
        item.frame = static_cast<std::uint8_t>(mav::MavFrame::kLocalFlu);
        item.command = static_cast<std::uint16_t>(mav::MavCmd::kNavWaypoint);
        item.x = static_cast<std::int32_t>(std::lround(path[request->seq].x() * 1e4));
        item.y = static_cast<std::int32_t>(std::lround(path[request->seq].y() * 1e4));
        gcs.send(item, gcs.now());
      }
    }
  }
  ASSERT_EQ(core.mission().waypoints().size(), 40u);
  gcs.command(mav::MavCmd::kMissionStart, 0.0f, gcs.now());
  const double start = gcs.now();
  while (gcs.now() < start + 200.0 && gcs.all<mav::MissionItemReached>().size() < 40)
    gcs.run(gcs.now() + 1.0, true, std::nullopt);
  gcs.run(gcs.now() + 1.0, true, std::nullopt);
  std::vector<std::uint16_t> reached;
  for (const auto& r : gcs.all<mav::MissionItemReached>())
    reached.push_back(r.seq);
  std::vector<std::uint16_t> expected(40);
  for (std::uint16_t i = 0; i < 40; ++i)
    expected[i] = i;
  EXPECT_EQ(reached, expected);
  const auto all = gcs.all<mav::IrgsMotionReport>();
  ASSERT_FALSE(all.empty());
  const std::uint16_t id = all.front().id;
  EXPECT_GE(id, FirmwareMotion::kFirstRobotId);
  const auto reports = reportsOf(gcs, id);
  expectWellFormed(reports);
  EXPECT_EQ(reports.back().kind, ReportKind::kDone);
  const auto kinds = kindsOf(reports);
  EXPECT_EQ(std::count(kinds.begin(), kinds.end(), ReportKind::kStarted), 1);
  EXPECT_EQ(reports[reports.size() - 2].index, 39);  // turning points carry item numbers
  EXPECT_NEAR(reports.back().distance_m, 40 * std::hypot(0.06, 0.03), 0.05);
  EXPECT_EQ(behaviourStates(gcs).back(), kSucceeded);
  EXPECT_TRUE(gcs.saidSomething("mission complete"));
}

// ---- The ground station's client on a lossy pipe ------------------------------------------------

// A ground station on the firmware's bytes: the pure motion client, the command protocol
// (comms::CommandManager, retried and acknowledged as over a Link), heartbeats; `lose` decides
// which of the robot's frames never arrive.
class Station {
 public:
  explicit Station(FirmwareCore& core) : core_(core) {}

  std::function<bool(const mav::Frame&)> lose = [](const mav::Frame&) { return false; };
  std::vector<motion::MotionReport> reports;
  std::size_t status_requests = 0;

  void start(const motion::Primitive& p) {
    client_.start(p, now_);
    flush();
  }
  void run(double until) {
    while (now_ + 1e-9 < until) {
      now_ += 0.01;
      if (now_ + 1e-9 >= next_hb_) {
        send(mav::Heartbeat{});
        next_hb_ = now_ + 0.5;
      }
      std::vector<mav::CommandLong> resend;
      commands_.tick(now_, resend);
      for (const auto& c : resend)
        send(c);
      client_.tick(now_);
      flush();
      core_.advance(now_);
      frames_.clear();
      decoder_.feed(core_.takeOutput(), frames_);
      for (const auto& f : frames_) {
        if (lose(f))
          continue;
        if (const auto ack = f.as<mav::CommandAck>())
          commands_.onAck(*ack, f.system_id, 255, 190, now_);
        client_.onFrame(f, now_);
      }
      client_.onSample(core_.simulator().time_s(), core_.simulator().odometryPose());
      for (auto& done : commands_.takeCompleted())
        if (done.callback)
          done.callback(done.result);
      flush();
      for (auto& r : client_.takeReports(1e9, now_))
        reports.push_back(r);
    }
  }
  double now() const { return now_; }

 private:
  template <class M>
  void send(const M& m) {
    core_.receiveBytes(encoder_.encode(m).view(), now_);
  }
  void flush() {
    comms::MotionClientOutput out = client_.takeOutput();
    for (const auto& w : out.waypoints)
      send(w);
    for (const auto& c : out.commands) {
      if (c.command.command == static_cast<std::uint16_t>(mav::MavCmd::kRequestMessage))
        ++status_requests;
      std::vector<mav::CommandLong> first;
      commands_.submit(
          c.command,
          [this, id = c.primitive_id](const comms::CommandResult& r) {
            client_.onCommandResult(id, r, now_);
          },
          now_, first);
      for (const auto& f : first)
        send(f);
    }
  }

  FirmwareCore& core_;
  comms::MavlinkMotionClient client_;
  comms::CommandManager commands_;
  mav::FrameEncoder encoder_{255, 190};
  mav::FrameDecoder decoder_;
  std::vector<mav::Frame> frames_;
  double now_ = 0.0;
  double next_hb_ = 0.0;
};

std::vector<ReportKind> kindsFor(const std::vector<motion::MotionReport>& reports,
                                 std::uint16_t id) {
  std::vector<ReportKind> out;
  for (const auto& r : reports)
    if (r.id == id)
      out.push_back(r.kind);
  return out;
}

TEST(FirmwareMotion, EveryLostReportFrameIsMadeUpByTheGroundStation) {
  FirmwareCore core = makeCore(room(false));
  Station station(core);
  // Not one IRGS_MOTION_REPORT arrives: the statuses and the acks carry it all.
  station.lose = [](const mav::Frame& f) { return f.message_id == mav::IrgsMotionReport::kId; };
  station.run(0.1);
  motion::SegmentsSpec spec;
  spec.append(Vec2(0.5, 0.0));
  spec.append(Vec2(0.5, 0.5));
  station.start({171, spec});
  station.run(20.0);
  EXPECT_EQ(kindsFor(station.reports, 171),
            (std::vector{ReportKind::kStarted, ReportKind::kTurningPoint, ReportKind::kTurningPoint,
                         ReportKind::kDone}));
  // A turn whose final report and status on change are lost: the status the ground station
  // asks for after 3 s of silence ends it.
  station.lose = [](const mav::Frame& f) {
    if (const auto s = f.as<mav::IrgsBehaviourStatus>())
      return s->state != kRunning && s->id == 172 &&
             s->report == static_cast<std::uint8_t>(mav::IrgsMotionReportKind::kDone);
    return f.message_id == mav::IrgsMotionReport::kId &&
           f.as<mav::IrgsMotionReport>()->kind ==
               static_cast<std::uint8_t>(mav::IrgsMotionReportKind::kDone);
  };
  station.start({172, motion::TurnSpec{0.3, false, 0.0, 0.0}});
  station.run(22.0);
  EXPECT_EQ(kindsFor(station.reports, 172), (std::vector{ReportKind::kStarted}));
  const std::size_t requests = station.status_requests;
  station.lose = [](const mav::Frame&) { return false; };
  station.run(28.0);
  EXPECT_GT(station.status_requests, requests);
  EXPECT_EQ(kindsFor(station.reports, 172), (std::vector{ReportKind::kStarted, ReportKind::kDone}));
}

TEST(FirmwareMotion, ALostAckMakesTheGroundStationRetryWithoutARestart) {
  FirmwareCore core = makeCore(room(false));
  Station station(core);
  int acks_lost = 0;
  station.lose = [&](const mav::Frame& f) {
    return f.message_id == mav::CommandAck::kId && acks_lost++ < 2;  // two acks lost
  };
  station.run(0.1);
  station.start({181, motion::DriveSpec{0.5, 0.2, false, 0.0}});
  station.run(8.0);
  EXPECT_EQ(kindsFor(station.reports, 181), (std::vector{ReportKind::kStarted, ReportKind::kDone}));
  EXPECT_EQ(acks_lost, 3);  // the third transmission's ack arrived
  EXPECT_NEAR(core.simulator().odometryPose().x, 0.5, 0.015);
}

}  // namespace
}  // namespace irgs::app
