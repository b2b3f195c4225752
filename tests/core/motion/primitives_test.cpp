// The robot-side motion primitives on the ideal simulator (no odometry error), on small literal
// situations: an empty room, one wall, a few waypoints.

#include <gtest/gtest.h>

#include <cmath>

#include "core/motion/host_adapters.hpp"
#include "core/motion/motion_executor.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/world/world_map.hpp"
#include "tests/core/behaviour/behaviour_test_support.hpp"
#include "tests/core/motion/motion_test_support.hpp"

namespace irgs::motion {
namespace {

using test::runPrimitive;

// A 6 m x 6 m room centred on the origin.
WorldMap room() {
  WorldMap map;
  map.name = "room";
  Wall wall;
  wall.id = "outline";
  wall.points = {{-3, -3}, {3, -3}, {3, 3}, {-3, 3}};
  wall.closed = true;
  map.walls.push_back(wall);
  return map;
}

struct Rig {
  RobotProfile profile = test::thesisRobot();
  Simulator sim{room(), profile, idealSimConfig()};
  MotionExecutor executor{motionGeometryOf(profile)};
  explicit Rig(Pose2 start = {}) { sim.resetPose(start); }
};

Primitive turnBy(double angle_rad, std::uint16_t id = 1) {
  TurnSpec s;
  s.angle_rad = angle_rad;
  return {id, s};
}

TEST(TurnPrimitive, TurnsAQuarterTurnAndEndsAtRestOnTheHeading) {
  Rig rig;
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, turnBy(0.5 * kPi), 20.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.kinds(), (std::vector{ReportKind::kStarted, ReportKind::kDone}));
  EXPECT_NEAR(run.odometry.theta, 0.5 * kPi, degToRad(1.0));
  EXPECT_NEAR(run.last().distance_m, 0.5 * kPi, degToRad(1.0));
}

TEST(TurnPrimitive, AFullScanTurnComesBackToTheStartHeading) {
  Rig rig;
  TurnSpec s;
  s.angle_rad = 2.0 * kPi;
  s.rate_radps = 0.8;
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {7, s}, 30.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.last().kind, ReportKind::kDone);
  EXPECT_EQ(run.last().id, 7);
  EXPECT_NEAR(run.last().distance_m, 2.0 * kPi, degToRad(1.0));
  EXPECT_NEAR(wrapAngle(run.odometry.theta), 0.0, degToRad(1.0));
  EXPECT_GT(run.time_s, 2.0 * kPi / 0.8);  // at the asked rate, not faster
}

TEST(TurnPrimitive, ToAHeadingInQuantaTurnsByTheNearestMultiple) {
  Rig rig;
  TurnSpec s;
  s.angle_rad = degToRad(37.0);
  s.absolute = true;
  s.quantum_rad = degToRad(15.0);
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {1, s}, 20.0);
  ASSERT_TRUE(run.finished);
  EXPECT_NEAR(run.odometry.theta, degToRad(30.0), degToRad(1.0));
}

TEST(DrivePrimitive, DrivesAMetreAndStopsOnIt) {
  Rig rig;
  DriveSpec s;
  s.distance_m = 1.0;
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {1, s}, 20.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.last().kind, ReportKind::kDone);
  EXPECT_NEAR(run.odometry.x, 1.0, 0.02);
  EXPECT_NEAR(run.odometry.y, 0.0, 0.01);
  EXPECT_NEAR(run.last().distance_m, 1.0, 0.02);
}

TEST(DrivePrimitive, BacksUpANegativeDistance) {
  Rig rig;
  DriveSpec s;
  s.distance_m = -0.2;
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {1, s}, 20.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.last().kind, ReportKind::kDone);
  EXPECT_NEAR(run.odometry.x, -0.2, 0.02);
}

TEST(DrivePrimitive, StopsAtAWallAheadBeforeTouchingIt) {
  Rig rig({2.0, 0.0, 0.0});  // the wall at x = 3 is 1 m ahead
  DriveSpec s;
  s.distance_m = 2.0;
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {1, s}, 20.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.last().kind, ReportKind::kFrontWall);
  EXPECT_EQ(rig.sim.bumpers(), 0u);
  EXPECT_LT(run.truth.x, 3.0 - rig.executor.settings().stopClearance() + 0.1);
  EXPECT_GT(run.truth.x, 2.3);
}

TEST(DrivePrimitive, WithoutTheWallStopABumperEndsIt) {
  Rig rig({2.0, 0.0, 0.0});
  DriveSpec s;
  s.distance_m = 2.0;
  s.stop_at_wall = false;
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {1, s}, 20.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.last().kind, ReportKind::kFailed);
  EXPECT_EQ(run.last().reason, Reason::kBumped);
}

TEST(SegmentsPrimitive, ReportsEachTurningPointAndEndsOnTheLast) {
  Rig rig;
  SegmentsSpec s;
  s.append({1.0, 0.0});
  s.append({1.0, 1.0});
  s.append({0.0, 1.0});
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {3, s}, 60.0);
  ASSERT_TRUE(run.finished);
  std::vector<int> points;
  for (const MotionReport& r : run.reports)
    if (r.kind == ReportKind::kTurningPoint)
      points.push_back(r.index);
  EXPECT_EQ(points, (std::vector{0, 1, 2}));
  EXPECT_EQ(run.last().kind, ReportKind::kDone);
  EXPECT_NEAR(run.odometry.x, 0.0, 0.02);
  EXPECT_NEAR(run.odometry.y, 1.0, 0.02);
  EXPECT_NEAR(run.last().distance_m, 3.0, 0.05);
}

TEST(SegmentsPrimitive, StopsBeforeAWallThatLiesBeforeTheWaypoint) {
  Rig rig({1.0, 0.0, 0.0});
  SegmentsSpec s;
  s.append({4.0, 0.0});  // beyond the wall at x = 3
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {1, s}, 30.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.last().kind, ReportKind::kFrontWall);
  EXPECT_EQ(rig.sim.bumpers(), 0u);
}

TEST(FollowPathPrimitive, ConvergesOntoThePathAndReachesItsEnd) {
  Rig rig({0.0, 0.3, 0.0});  // 30 cm left of the first piece
  FollowPathSpec s;
  s.append({2.0, 0.0});
  s.append({2.0, 2.0});
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {1, s}, 60.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.last().kind, ReportKind::kDone);
  EXPECT_NEAR(run.odometry.x, 2.0, 0.1);
  EXPECT_NEAR(run.odometry.y, 2.0, 0.05);
}

TEST(FollowWallPrimitive, FollowsTheWallReportingModesAndMarksUntilTheTravelLimit) {
  // Beside the south wall (y = -3), 0.3 m from it, heading east: the wall is on the right.
  Rig rig({-2.0, -2.7, 0.0});
  FollowWallSpec s;
  s.wall_on_left = false;
  s.distance_m = 0.3;
  s.travel_limit_m = 3.0;
  s.report_every_m = 1.0;
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {1, s}, 60.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.last().kind, ReportKind::kDone);
  int marks = 0;
  bool followed = false;
  for (const MotionReport& r : run.reports) {
    marks += r.kind == ReportKind::kDistanceMark ? 1 : 0;
    followed |= r.kind == ReportKind::kMode && r.index == static_cast<int>(WallFollowMode::kFollow);
  }
  EXPECT_EQ(marks, 3);
  EXPECT_TRUE(followed);
  EXPECT_NEAR(run.truth.y, -2.7, 0.05);  // kept the set distance
  EXPECT_NEAR(run.last().distance_m, 3.0, 0.05);
}

TEST(FollowWallPrimitive, StopsAtTheWallAheadWhenAsked) {
  Rig rig({1.5, -2.7, 0.0});  // the east wall 1.5 m ahead
  FollowWallSpec s;
  s.wall_on_left = false;
  s.stop_at_front_wall = true;
  const test::PrimitiveRun run = runPrimitive(rig.sim, rig.executor, {1, s}, 60.0);
  ASSERT_TRUE(run.finished);
  EXPECT_EQ(run.last().kind, ReportKind::kFrontWall);
  EXPECT_GT(run.truth.x, 2.4);
  EXPECT_EQ(rig.sim.bumpers(), 0u);
}

TEST(MotionExecutor, RefusesIdZeroAndInvalidSpecsWithAReason) {
  Rig rig;
  const MotionInput now = motionInputOf(rig.sim.step());
  EXPECT_FALSE(rig.executor.start(turnBy(1.0, 0), now));
  DriveSpec nan;
  nan.distance_m = std::nan("");
  EXPECT_FALSE(rig.executor.start({2, nan}, now));
  MotionReport r;
  ASSERT_TRUE(rig.executor.popReport(r));
  EXPECT_EQ(r.kind, ReportKind::kRefused);
  EXPECT_EQ(r.reason, Reason::kInvalid);
  ASSERT_TRUE(rig.executor.popReport(r));
  EXPECT_EQ(r.id, 2);
  EXPECT_EQ(r.kind, ReportKind::kRefused);
  EXPECT_FALSE(rig.executor.running());
}

TEST(MotionExecutor, RefusesWallFollowingOnASideWithoutSonars) {
  RobotProfile profile = test::thesisRobot();
  std::erase_if(profile.sonars, [](const SonarSpec& s) { return s.mount.theta < -1.0; });
  MotionExecutor executor(motionGeometryOf(profile));
  FollowWallSpec s;
  s.wall_on_left = false;
  EXPECT_FALSE(executor.start({1, s}, MotionInput{}));
  MotionReport r;
  ASSERT_TRUE(executor.popReport(r));
  EXPECT_EQ(r.reason, Reason::kNoSensors);
}

TEST(MotionExecutor, ANewPrimitiveCancelsTheRunningOne) {
  Rig rig;
  const MotionInput now = motionInputOf(rig.sim.step());
  ASSERT_TRUE(rig.executor.start(turnBy(1.0, 1), now));
  ASSERT_TRUE(rig.executor.start(turnBy(-1.0, 2), now));
  rig.executor.cancel(now);
  std::vector<std::pair<int, ReportKind>> seen;
  MotionReport r;
  while (rig.executor.popReport(r))
    seen.emplace_back(r.id, r.kind);
  EXPECT_EQ(seen, (std::vector<std::pair<int, ReportKind>>{{1, ReportKind::kStarted},
                                                           {1, ReportKind::kCancelled},
                                                           {2, ReportKind::kStarted},
                                                           {2, ReportKind::kCancelled}}));
  EXPECT_EQ(rig.executor.step(now), VelocityCommand{});
}

TEST(MotionExecutor, AFullReportQueueDropsTheOldestAndCountsIt) {
  Rig rig;
  const MotionInput now = motionInputOf(rig.sim.step());
  for (std::uint16_t id = 1; id <= MotionExecutor::kReportCapacity + 3; ++id)
    rig.executor.start(turnBy(0.1, id), now);  // kCancelled + kStarted each after the first
  EXPECT_EQ(rig.executor.pendingReports(), MotionExecutor::kReportCapacity);
  EXPECT_GT(rig.executor.droppedReports(), 0u);
  MotionReport r, newest;
  while (rig.executor.popReport(r))
    newest = r;
  EXPECT_EQ(newest.id, MotionExecutor::kReportCapacity + 3);
  EXPECT_EQ(newest.kind, ReportKind::kStarted);
}

TEST(MotionExecutor, WaypointsThatMakeNoProgressWithoutAnyContactFailAfterTheWatchdog) {
  // Held by something neither the bumpers nor the drive's stall report see (a robot without
  // stall detection): only the no-progress watchdog ends it.
  Rig rig;
  MotionInput in = motionInputOf(rig.sim.step());
  SegmentsSpec spec;
  spec.append(Vec2(1.0, 0.0));  // straight ahead of the rig's start pose
  spec.stop_at_wall = false;
  ASSERT_TRUE(rig.executor.start({7, spec}, in));
  const MotionSettings settings;
  for (int i = 0; i < static_cast<int>((settings.no_progress_s + 1.0) / 0.01); ++i) {
    in.time_s += 0.01;
    rig.executor.step(in);  // the odometry never moves
  }
  MotionReport r, last;
  while (rig.executor.popReport(r))
    last = r;
  EXPECT_EQ(last.kind, ReportKind::kFailed);
  EXPECT_EQ(last.reason, Reason::kNoProgress);
}

TEST(MotionExecutor, ATurnHeldInContactEndsBlocked) {
  Rig rig;
  MotionInput in = motionInputOf(rig.sim.step());
  ASSERT_TRUE(rig.executor.start(turnBy(1.0), in));
  in.bumpers = 1;  // pressed, and the body does not turn
  for (int i = 0; i < 150; ++i) {
    in.time_s += 0.01;
    rig.executor.step(in);
  }
  MotionReport r, last;
  while (rig.executor.popReport(r))
    last = r;
  EXPECT_EQ(last.kind, ReportKind::kFailed);
  EXPECT_EQ(last.reason, Reason::kBlocked);
  EXPECT_NEAR(last.time_s - 0.01, in.time_s - 0.49, 0.02);  // after blocked_s = 1 s
}

}  // namespace
}  // namespace irgs::motion

namespace irgs::motion {
namespace {

TEST(MotionExecutor, GivesTheHeadingItSteersTowardForRobotsThatHoldOneThemselves) {
  Rig rig;
  MotionInput in = motionInputOf(rig.sim.step());
  TurnSpec turn;
  turn.angle_rad = 0.5;
  ASSERT_TRUE(rig.executor.start({1, turn}, in));
  rig.executor.step(in);
  ASSERT_TRUE(rig.executor.headingSetpoint().has_value());
  EXPECT_NEAR(*rig.executor.headingSetpoint(), 0.5, 1e-9);
  DriveSpec drive;
  drive.distance_m = 1.0;
  in.odometry.theta = 0.2;
  ASSERT_TRUE(rig.executor.start({2, drive}, in));
  in.odometry.theta = 0.25;  // drifted: the setpoint stays the start heading
  rig.executor.step(in);
  EXPECT_NEAR(*rig.executor.headingSetpoint(), 0.2, 1e-9);
  rig.executor.cancel(in);
  rig.executor.step(in);
  EXPECT_FALSE(rig.executor.headingSetpoint().has_value());
}

}  // namespace
}  // namespace irgs::motion
