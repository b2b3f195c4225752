// The pieces of the map-building mission and the other host missions, each on a small literal
// situation.

#include <gtest/gtest.h>

#include <cmath>

#include "core/mapping/occupancy_grid.hpp"
#include "core/mission/behaviour_mission.hpp"
#include "core/mission/explored_record.hpp"
#include "core/mission/interior_targets.hpp"
#include "core/mission/loop_tracker.hpp"
#include "core/mission/mission_feed.hpp"
#include "core/mission/mission_runner.hpp"
#include "core/mission/travel_mission.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/sim/simulated_robot.hpp"
#include "tests/core/behaviour/behaviour_test_support.hpp"

namespace irgs {
namespace {

// A square loop of side 2 m driven clockwise (wall on the left), from (0, 0) heading +y... the
// robot goes up, right, down, left.
std::vector<Pose2> clockwiseSquare(double step_m) {
  std::vector<Pose2> poses;
  const Vec2 corners[] = {{0, 0}, {0, 2}, {2, 2}, {2, 0}, {0, 0}};
  for (int side = 0; side < 4; ++side) {
    const Vec2 a = corners[side], b = corners[side + 1];
    const Vec2 d = (b - a).normalized();
    const double heading = std::atan2(d.y(), d.x());
    for (double s = 0.0; s < 2.0 - 1e-9; s += step_m) {
      const Vec2 p = a + s * d;
      poses.push_back({p.x(), p.y(), heading});
    }
  }
  poses.push_back({0.0, 0.0, 0.5 * kPi});
  return poses;
}

TEST(LoopTracker, DropsIndicesAtTheSpacingOnlyOnceFollowing) {
  LoopTracker loops(0.5, 0.35, 1.5);
  EXPECT_FALSE(loops.onPose({0, 0, 0}, false));
  EXPECT_FALSE(loops.started());
  for (int i = 0; i <= 20; ++i)
    loops.onPose({0.1 * i, 0.0, 0.0}, true);
  // First index at x = 0, then 0.5, 1.0, 1.5, 2.0.
  ASSERT_EQ(loops.indices().size(), 5u);
  EXPECT_NEAR(loops.indices()[1].x(), 0.5, 1e-9);
  EXPECT_NEAR(loops.loopDistance_m(), 2.0, 1e-9);
}

TEST(LoopTracker, ClosesAClockwiseSquareAtItsFirstIndexWithANegativeArea) {
  LoopTracker loops(0.5, 0.35, 1.5);
  std::optional<std::size_t> closed;
  Pose2 at;
  for (const Pose2& p : clockwiseSquare(0.05)) {
    at = p;
    if ((closed = loops.onPose(p, true)))
      break;
  }
  ASSERT_TRUE(closed.has_value());
  EXPECT_EQ(*closed, 0u);
  const TracedLoop loop = loops.loopFrom(*closed, at.position());
  EXPECT_FALSE(loop.obstacle);
  EXPECT_NEAR(loop.signed_area_m2, -4.0, 0.6);  // indices every 0.5 m round a 2 m square
}

TEST(LoopTracker, DoesNotCloseWhenComingBackTheOtherWay) {
  LoopTracker loops(0.5, 0.35, 1.5);
  for (int i = 0; i <= 20; ++i)
    loops.onPose({0.1 * i, 0.0, 0.0}, true);
  for (int i = 20; i >= 0; --i)  // back along the same line, heading the opposite way
    EXPECT_FALSE(loops.onPose({0.1 * i, 0.05, kPi}, true)) << i;
}

// The follower lost the wall and turned back along its own path, then round again (tb3_sandbox
// once closed such a 0.04 m2 "outline" of six indices and ended the exploration there).
TEST(LoopTracker, APathThatCameBackOnItselfEnclosesNothingAndClosesNoLoop) {
  LoopTracker loops(0.5, 0.35, 1.5);
  for (int i = 0; i <= 20; ++i)
    loops.onPose({0.1 * i, 0.0, 0.0}, true);
  for (int i = 20; i >= 0; --i)
    loops.onPose({0.1 * i, 0.05, kPi}, true);
  for (int i = 0; i <= 5; ++i)  // heading as at the first index, within reach of it
    EXPECT_FALSE(loops.onPose({0.1 * i, 0.02, 0.0}, true)) << i;
}

ExploredRecord roomWithOneObstacle() {
  ExploredRecord record(0.6);
  TracedLoop outline;
  outline.indices = {{0, 0}, {0, 6}, {6, 6}, {6, 0}};  // clockwise
  record.setOutline(outline);
  TracedLoop box;
  box.indices = {{2, 2}, {3, 2}, {3, 3}, {2, 3}};
  box.obstacle = true;
  record.addObstacle(box);
  return record;
}

TEST(ExploredRecord, ExplainsPointsNearTheOutlineAndInsideOrNearObstacles) {
  const ExploredRecord record = roomWithOneObstacle();
  EXPECT_TRUE(record.insideOutline({1, 1}));
  EXPECT_FALSE(record.insideOutline({7, 1}));
  EXPECT_TRUE(record.explained({0.3, 3.0}));   // beside a wall
  EXPECT_TRUE(record.explained({2.5, 2.5}));   // inside the box's loop
  EXPECT_TRUE(record.explained({3.4, 2.5}));   // beside it
  EXPECT_FALSE(record.explained({4.5, 4.5}));  // in the open
}

TEST(ExploredRecord, BlacklistAndSpotsVisitedByTwoLoops) {
  ExploredRecord record = roomWithOneObstacle();
  record.blacklist({4, 4}, 0.5);
  EXPECT_TRUE(record.listed({4.3, 4.0}));
  EXPECT_FALSE(record.listed({4.6, 4.0}));
  record.addObstacleAnchor({5, 1});
  EXPECT_FALSE(record.visitedOften({5, 1}));
  record.addObstacleAnchor({5.5, 1});
  EXPECT_TRUE(record.visitedOften({5.2, 1.0}));
  EXPECT_FALSE(record.visitedOften({3.0, 5.0}));
}

// Paints a 4 m x 4 m room into a grid with narrow sonar cones: the inside seen free (rows of
// cones without an echo), the walls and a 20 cm post seen occupied (echo cones onto them); with
// the strip x > 3 m never seen.
OccupancyGrid roomGrid(bool with_unknown_strip, bool with_post) {
  OccupancyGrid grid(0.05);
  SonarInverseModel model;
  model.no_echo_free_range_m = 10.0;
  const double beam = 0.02;
  const double x_end = with_unknown_strip ? 3.0 : 3.95;
  for (int pass = 0; pass < 4; ++pass) {
    for (double y = 0.1; y < 3.95; y += 0.025)
      grid.integrateSonar({0.06, y}, 0.0, beam, x_end - 0.06, false, model);
    for (double y = 0.1; y < 3.95; y += 0.025) {                     // the west and east walls
      grid.integrateSonar({0.5, y}, kPi, beam, 0.475, true, model);  // onto cell centres
      if (!with_unknown_strip)
        grid.integrateSonar({3.5, y}, 0.0, beam, 0.475, true, model);
    }
    for (double x = 0.1; x < x_end; x += 0.025) {  // the south and north walls
      grid.integrateSonar({x, 0.5}, -0.5 * kPi, beam, 0.475, true, model);
      grid.integrateSonar({x, 3.5}, 0.5 * kPi, beam, 0.475, true, model);
    }
    if (with_post)
      for (double y = 1.9; y <= 2.1; y += 0.025)
        grid.integrateSonar({1.5, y}, 0.0, beam, 0.425, true, model);
  }
  return grid;
}

ExploredRecord roomRecord() {
  ExploredRecord record(0.6);
  TracedLoop outline;
  outline.indices = {{0.3, 0.3}, {0.3, 3.7}, {3.7, 3.7}, {3.7, 0.3}};
  record.setOutline(outline);
  return record;
}

TEST(InteriorTargets, GoesToTheUnknownStripAlongAPathThroughFreeSpace) {
  const OccupancyGrid grid = roomGrid(true, false);
  const OccupancyGrid explore(0.05);
  InteriorSearchConfig config;
  config.explore_range_m = 0.0;
  const auto target = chooseInteriorTarget({1.0, 2.0, 0.0}, grid, explore, roomRecord(), config);
  ASSERT_TRUE(target.has_value());
  EXPECT_FALSE(target->obstacle);
  EXPECT_GT(target->position.x(), 2.3);  // at the strip's edge, not in it
  EXPECT_LT(target->position.x(), 3.1);
  EXPECT_NEAR(target->path.front().x(), 1.0, 1e-9);  // from where the robot stands
  EXPECT_EQ(target->path.back(), target->position);
}

TEST(InteriorTargets, AnUnexplainedPostInsideIsATarget) {
  const OccupancyGrid grid = roomGrid(false, true);
  const OccupancyGrid explore(0.05);
  InteriorSearchConfig config;
  config.explore_range_m = 0.0;
  const auto target = chooseInteriorTarget({1.0, 1.0, 0.0}, grid, explore, roomRecord(), config);
  ASSERT_TRUE(target.has_value());
  EXPECT_TRUE(target->obstacle);
  EXPECT_LT((target->obstacle_point - Vec2(2.0, 2.0)).norm(), 0.15);
}

TEST(InteriorTargets, NothingLeftWhenTheRoomIsKnownAndExplained) {
  const OccupancyGrid grid = roomGrid(false, false);
  const OccupancyGrid explore(0.05);
  InteriorSearchConfig config;
  config.explore_range_m = 0.0;
  EXPECT_FALSE(chooseInteriorTarget({1.0, 1.0, 0.0}, grid, explore, roomRecord(), config));
  ExploredRecord no_outline(0.6);
  EXPECT_FALSE(chooseInteriorTarget({1.0, 1.0, 0.0}, grid, explore, no_outline, config));
}

WorldMap emptyRoom() {
  WorldMap map;
  Wall wall;
  wall.points = {{-3, -3}, {3, -3}, {3, 3}, {-3, 3}};
  wall.closed = true;
  map.walls.push_back(wall);
  return map;
}

// Runs a mission on the in-process robot until it finishes (one step per update).
BehaviourStatus runToEnd(Mission& mission, SimulatedRobot& robot, double budget_s) {
  MissionRunner runner;
  EXPECT_FALSE(runner.start(mission, robot).has_value());
  for (double t = 0.0; t < budget_s && runner.running(); t += robot.simulator().config().dt_s) {
    robot.singleStep();
    runner.feed(robot.update(0.0));
  }
  return runner.status();
}

TEST(TravelMission, ReportsEveryTurningPointAndArrives) {
  SimulatedRobot robot(emptyRoom(), test::thesisRobot(), idealSimConfig());
  TravelMission travel({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {.turn_quantum_rad = 0.0});
  const BehaviourStatus s = runToEnd(travel, robot, 120.0);
  EXPECT_TRUE(s.finished);
  EXPECT_FALSE(s.failed) << s.message;
  EXPECT_EQ(travel.reached(), 3u);
  EXPECT_EQ(travel.arrivalPositions().size(), 3u);
  EXPECT_NEAR(robot.simulator().truePose().y, 1.0, 0.03);
}

TEST(TravelMission, ALongPathGoesInChunksOfOnePrimitiveEach) {
  SimulatedRobot robot(emptyRoom(), test::thesisRobot(), idealSimConfig());
  std::vector<Vec2> zigzag{{-2.5, -2.0}};
  for (int i = 1; i <= 40; ++i)
    zigzag.push_back({-2.5 + 0.12 * i, i % 2 ? -1.8 : -2.0});
  robot.simulator().resetPose({-2.5, -2.0, 0.0});
  TravelMission travel(zigzag, {.speed_mps = 0.2, .turn_quantum_rad = 0.0});
  MissionRunner runner;
  ASSERT_FALSE(runner.start(travel, robot));
  for (double t = 0.0; t < 600.0 && runner.running(); t += 0.01) {
    robot.singleStep();
    runner.feed(robot.update(0.0));
  }
  EXPECT_FALSE(runner.status().failed) << runner.status().message;
  EXPECT_EQ(travel.reached(), 40u);
  EXPECT_EQ(runner.primitivesStarted(), 2);  // 32 + 8 turning points
}

TEST(TravelMission, AWallOnTheWayEndsItFailedWithWhere) {
  SimulatedRobot robot(emptyRoom(), test::thesisRobot(), idealSimConfig());
  TravelMission travel({{0, 0}, {5, 0}});
  const BehaviourStatus s = runToEnd(travel, robot, 120.0);
  EXPECT_TRUE(s.failed);
  EXPECT_NE(s.message.find("blocked ahead"), std::string::npos) << s.message;
}

TEST(MissionRunner, RefusesAPrimitiveMissionOnARobotWithoutPrimitivesAndASecondMission) {
  class VelocityOnly : public Robot {
   public:
    const RobotProfile& profile() const override { return profile_; }
    std::string describe() const override { return "test"; }
    void drive(const VelocityCommand&) override {}
    void stop() override {}
    std::vector<TelemetrySample> update(double) override { return {}; }
    RobotProfile profile_;
  } robot;
  MissionRunner runner;
  TravelMission travel({{0, 0}, {1, 0}});
  const auto refused = runner.start(travel, robot);
  ASSERT_TRUE(refused.has_value());
  EXPECT_NE(refused->find("motion primitives"), std::string::npos);

  class Idle : public Behaviour {
   public:
    VelocityCommand onSample(const TelemetrySample&) override { return {0.1, 0.0}; }
    BehaviourStatus status() const override { return {}; }
    std::string_view name() const override { return "idle"; }
  } idle;
  BehaviourMission velocity(idle);
  ASSERT_FALSE(runner.start(velocity, robot));
  BehaviourMission another(idle);
  const auto busy = runner.start(another, robot);
  ASSERT_TRUE(busy.has_value());
  EXPECT_NE(busy->find("is running"), std::string::npos);
  runner.abort("test over");
  EXPECT_TRUE(runner.status().failed);
  EXPECT_EQ(runner.status().message, "test over");
}

TEST(MissionRunner, DeliversReportsBeforeTheSamplesThatFollowThem) {
  struct Recorder : Mission {
    std::vector<std::string> seen;
    void onSample(const TelemetrySample& s) override {
      seen.push_back("s" + std::to_string(static_cast<int>(std::lround(s.time_s * 100))));
    }
    void onReport(const motion::MotionReport& r) override {
      seen.push_back(std::string("r") + motion::toString(r.kind));
    }
    std::optional<MissionRequest> takeRequest() override {
      if (sent)
        return std::nullopt;
      sent = true;
      motion::TurnSpec turn;
      turn.angle_rad = 0.02;
      return StartPrimitive{{1, turn}};
    }
    BehaviourStatus status() const override { return {}; }
    std::string_view name() const override { return "recorder"; }
    bool sent = false;
  } recorder;
  SimulatedRobot robot(emptyRoom(), test::thesisRobot(), idealSimConfig());
  MissionRunner runner;
  ASSERT_FALSE(runner.start(recorder, robot));
  for (int i = 0; i < 3; ++i)
    robot.singleStep();
  runner.feed(robot.update(0.0));
  // The start (at time 0) is reported before the first sample (0.01).
  ASSERT_GE(recorder.seen.size(), 4u);
  EXPECT_EQ(recorder.seen[0], "rstarted");
  EXPECT_EQ(recorder.seen[1], "s1");
}

motion::MotionReport reportAt(double time_s, motion::ReportKind kind) {
  motion::MotionReport r;
  r.time_s = time_s;
  r.kind = kind;
  return r;
}

TelemetrySample sampleAt(double time_s) {
  TelemetrySample s;
  s.time_s = time_s;
  return s;
}

// "r<time>" and "s<time>" in hundredths, in the order delivered.
struct FeedLog {
  std::vector<std::string> seen;
  bool onReport(const motion::MotionReport& r) {
    seen.push_back("r" + std::to_string(std::lround(r.time_s * 100)));
    return true;
  }
  bool onSample(const TelemetrySample& s) {
    seen.push_back("s" + std::to_string(std::lround(s.time_s * 100)));
    return true;
  }
};

TEST(MissionFeed, ReportsGoBeforeTheFirstSampleAtOrAfterThemAndNewerOnesAfterTheNewest) {
  using motion::ReportKind;
  std::vector<motion::MotionReport> reports = {reportAt(0.10, ReportKind::kStarted),
                                               reportAt(0.20, ReportKind::kTurningPoint),
                                               reportAt(0.35, ReportKind::kDone)};
  const std::vector<TelemetrySample> samples = {sampleAt(0.10), sampleAt(0.20), sampleAt(0.30)};
  FeedLog log;
  feedInTimeOrder(
      reports, samples, [&](const auto& r) { return log.onReport(r); },
      [&](const auto& s) { return log.onSample(s); });
  // The final report is newer than every sample (the telemetry of its moment is late): it goes
  // now, not with a sample that may never come.
  EXPECT_EQ(log.seen, (std::vector<std::string>{"r10", "s10", "r20", "s20", "s30", "r35"}));
  EXPECT_TRUE(reports.empty());
}

TEST(MissionFeed, StopsWhereTheMissionFinished) {
  std::vector<motion::MotionReport> reports = {reportAt(0.10, motion::ReportKind::kDone),
                                               reportAt(0.25, motion::ReportKind::kStarted)};
  const std::vector<TelemetrySample> samples = {sampleAt(0.10), sampleAt(0.20), sampleAt(0.30)};
  FeedLog log;
  feedInTimeOrder(
      reports, samples, [&](const auto& r) { return log.onReport(r); },
      [&](const auto& s) {
        log.onSample(s);
        return s.time_s < 0.15;  // finished on the sample at 0.2
      });
  EXPECT_EQ(log.seen, (std::vector<std::string>{"r10", "s10", "s20"}));
  EXPECT_TRUE(reports.empty()) << "what was not delivered is not this mission's any more";
}

}  // namespace
}  // namespace irgs
