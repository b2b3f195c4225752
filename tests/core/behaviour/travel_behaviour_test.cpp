#include "core/behaviour/travel_behaviour.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/planning/astar.hpp"
#include "core/planning/path_amendment.hpp"
#include "core/planning/planning_grid.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulator.hpp"
#include "core/world/map_file.hpp"

namespace irgs {
namespace {

RobotProfile thesisRobot() {
  RobotProfileResult result =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  if (!result.profile)
    throw std::runtime_error("thesis_robot.json does not load");
  return *result.profile;
}

WorldMap squareRoom(double half_m, const Pose2& start) {
  WorldMap map;
  map.name = "room";
  Wall wall;
  wall.id = "room";
  wall.points = {Vec2(-half_m, -half_m), Vec2(half_m, -half_m), Vec2(half_m, half_m),
                 Vec2(-half_m, half_m)};
  wall.closed = true;
  map.walls.push_back(wall);
  map.start = start;
  return map;
}

struct RunResult {
  double time_s = 0.0;
  int samples = 0;
  std::vector<std::string> messages;  // every change of status().message, in order
};

// Closes the loop sample by sample, as the GUI and irgs-sim do; stops when the behaviour
// finishes and the robot has come to rest, or at max_time_s.
RunResult run(Simulator& sim, TravelBehaviour& behaviour, double max_time_s) {
  RunResult result;
  std::string last;
  while (sim.time_s() < max_time_s) {
    const TelemetrySample sample = sim.step();
    sim.setCommand(behaviour.onSample(sample));
    ++result.samples;
    const BehaviourStatus status = behaviour.status();
    if (status.message != last) {
      last = status.message;
      result.messages.push_back(last);
    }
    if (status.finished && std::abs(sim.trueVelocity().linear_mps) < 1e-6 &&
        std::abs(sim.trueVelocity().angular_radps) < 1e-6)
      break;
  }
  result.time_s = sim.time_s();
  return result;
}

Simulator makeSim(const WorldMap& map) {
  SimConfig config;
  config.seed = 3;
  Simulator sim(map, thesisRobot(), config);
  sim.resetPose(map.start);
  return sim;
}

TEST(TravelBehaviour, DrivesAnLShapedPlanAndStopsAtTheGoal) {
  const WorldMap map = squareRoom(2.0, {-1.0, -1.0, 0.0});
  Simulator sim = makeSim(map);
  const TravelPlan plan = makeTravelPlan({{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}}, 0.0);
  ASSERT_EQ(plan.segments.size(), 2u);
  TravelBehaviour behaviour(plan, travelOptionsFor(sim.profile()));

  const RunResult result = run(sim, behaviour, 60.0);
  const BehaviourStatus status = behaviour.status();
  EXPECT_TRUE(status.finished);
  EXPECT_FALSE(status.failed) << status.message;
  EXPECT_DOUBLE_EQ(status.progress, 1.0);
  EXPECT_LT((sim.truePose().position() - Vec2(1.0, 1.0)).norm(), 0.03);
  ASSERT_EQ(behaviour.arrivals().size(), 2u);
  EXPECT_TRUE(behaviour.arrivals()[0].isApprox(Vec2(1.0, -1.0)));
  // One arrival report at the turning point, then the goal.
  ASSERT_EQ(result.messages.size(), 2u);
  EXPECT_EQ(result.messages[0], "arrived at turning point 1/1 (1.00, -1.00)");
  EXPECT_EQ(result.messages[1], "arrived at the goal (1.00, 1.00)");
  EXPECT_LT(result.time_s, 30.0);
}

TEST(TravelBehaviour, TurnsOnTheSpotBeforeEachLeg) {
  const WorldMap map = squareRoom(2.0, {0.0, 0.0, 0.0});
  Simulator sim = makeSim(map);
  // Straight behind the robot: a 180 degree turn in place, then 1 m.
  TravelBehaviour behaviour(makeTravelPlan({{0.0, 0.0}, {-1.0, 0.0}}, 0.0),
                            travelOptionsFor(sim.profile()));
  double max_offset = 0.0;
  while (!behaviour.status().finished && sim.time_s() < 30.0) {
    const TelemetrySample sample = sim.step();
    sim.setCommand(behaviour.onSample(sample));
    if (behaviour.phase() == TravelBehaviour::Phase::kTurn)
      max_offset = std::max(max_offset, sample.true_pose->position().norm());
  }
  EXPECT_FALSE(behaviour.status().failed) << behaviour.status().message;
  EXPECT_LT(max_offset, 0.005);  // the turn did not move the robot
  EXPECT_LT((sim.truePose().position() - Vec2(-1.0, 0.0)).norm(), 0.03);
  EXPECT_NEAR(std::abs(wrapAngle(sim.truePose().theta - kPi)), 0.0, degToRad(3.0));
}

TEST(TravelBehaviour, ReachesAGoalOnTheDefaultMapAlongTheAmendedAStarPath) {
  const MapLoadResult loaded =
      loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/default.json");
  ASSERT_TRUE(loaded.map.has_value());
  const WorldMap& map = *loaded.map;
  Simulator sim = makeSim(map);
  PlanningGridOptions grid_options;
  grid_options.robot_radius_m = sim.profile().bodyRadius() + 0.03;
  const PlanningGrid grid = planningGridFromWorld(map, 0.05, grid_options);
  const Vec2 goal(5.6, 3.2);  // the bedroom: through the study and the east doorway
  const PlanResult raw =
      planAStar(grid, *grid.worldToCell(map.start.position()), *grid.worldToCell(goal));
  ASSERT_TRUE(raw.found()) << toString(raw.status);
  std::vector<Vec2> path = raw.points;
  path.front() = map.start.position();
  path.back() = goal;
  const AmendResult amended = amendPath(grid, path, {});
  EXPECT_LT(amended.turns_after, amended.turns_before);
  TravelBehaviour behaviour(makeTravelPlan(amended.points, map.start.theta),
                            travelOptionsFor(sim.profile()));
  const RunResult result = run(sim, behaviour, 240.0);
  EXPECT_FALSE(behaviour.status().failed) << behaviour.status().message;
  EXPECT_TRUE(behaviour.status().finished);
  EXPECT_LT((sim.truePose().position() - goal).norm(), 0.05);
  EXPECT_EQ(behaviour.arrivals().size(), behaviour.plan().segments.size());
  EXPECT_EQ(sim.bumpers(), 0u);
  (void)result;
}

TEST(TravelBehaviour, GivesUpWhenAWallBlocksTheLeg) {
  const WorldMap map = squareRoom(1.0, {0.0, 0.0, 0.0});
  Simulator sim = makeSim(map);
  TravelBehaviour behaviour(makeTravelPlan({{0.0, 0.0}, {3.0, 0.0}}, 0.0),
                            travelOptionsFor(sim.profile()));
  run(sim, behaviour, 60.0);
  const BehaviourStatus status = behaviour.status();
  EXPECT_TRUE(status.finished);
  EXPECT_TRUE(status.failed);
  EXPECT_FALSE(status.message.empty());
  EXPECT_LT(sim.truePose().x, 1.0);
  // Finished: the command is zero from now on.
  const TelemetrySample sample = sim.step();
  EXPECT_EQ(behaviour.onSample(sample), VelocityCommand{});
}

TEST(TravelBehaviour, OpenLoopDrivesTheQuantisedHeadingForThePlannedDistance) {
  const WorldMap map = squareRoom(3.0, {0.0, 0.0, 0.0});
  Simulator sim = makeSim(map);
  // 10 degrees off the axis: quantised to 15 degrees (the nearest multiple).
  const Vec2 goal(2.0 * std::cos(degToRad(10.0)), 2.0 * std::sin(degToRad(10.0)));
  const TravelPlan plan = makeTravelPlan({{0.0, 0.0}, goal}, 0.0);
  ASSERT_EQ(plan.segments.size(), 1u);
  EXPECT_NEAR(plan.segments[0].heading_rad, degToRad(15.0), 1e-9);
  TravelOptions options = travelOptionsFor(sim.profile());
  options.steer_to_turning_points = false;
  TravelBehaviour open_loop(plan, options);
  run(sim, open_loop, 60.0);
  EXPECT_FALSE(open_loop.status().failed);
  const Vec2 expected(2.0 * std::cos(degToRad(15.0)), 2.0 * std::sin(degToRad(15.0)));
  EXPECT_LT((sim.truePose().position() - expected).norm(), 0.03);

  // Steering (the default) corrects the quantum's error and arrives at the goal itself.
  Simulator sim2 = makeSim(map);
  TravelBehaviour steered(plan, travelOptionsFor(sim2.profile()));
  run(sim2, steered, 60.0);
  EXPECT_LT((sim2.truePose().position() - goal).norm(), 0.03);
}

TEST(TravelBehaviour, ReportsProgressThatGrowsMonotonically) {
  const WorldMap map = squareRoom(2.0, {-1.0, 0.0, 0.0});
  Simulator sim = makeSim(map);
  TravelBehaviour behaviour(makeTravelPlan({{-1.0, 0.0}, {1.0, 0.0}}, 0.0),
                            travelOptionsFor(sim.profile()));
  double last = 0.0;
  bool halfway_seen = false;
  while (!behaviour.status().finished && sim.time_s() < 30.0) {
    sim.setCommand(behaviour.onSample(sim.step()));
    const double progress = behaviour.status().progress;
    EXPECT_GE(progress, last - 1e-12);
    halfway_seen = halfway_seen || (progress > 0.4 && progress < 0.6);
    last = progress;
  }
  EXPECT_TRUE(halfway_seen);
  EXPECT_DOUBLE_EQ(last, 1.0);
}

TEST(TravelBehaviour, AnEmptyPlanFinishesAtOnceWithAZeroCommand) {
  TravelBehaviour behaviour(TravelPlan{});
  EXPECT_TRUE(behaviour.status().finished);
  EXPECT_FALSE(behaviour.status().failed);
  EXPECT_EQ(behaviour.onSample(TelemetrySample{}), VelocityCommand{});
}

TEST(TravelBehaviour, IgnoresSamplesWithoutAFinitePose) {
  TravelBehaviour behaviour(makeTravelPlan({{0.0, 0.0}, {1.0, 0.0}}, 0.0));
  TelemetrySample sample;
  sample.odometry_pose.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(behaviour.onSample(sample), VelocityCommand{});
  EXPECT_FALSE(behaviour.status().finished);
}

TEST(TravelBehaviour, RejectsInvalidOptionsAndNonFinitePlans) {
  TravelOptions options;
  options.max_speed_mps = -1.0;
  EXPECT_TRUE(travelOptionsError(options).has_value());
  EXPECT_THROW(TravelBehaviour(TravelPlan{}, options), std::invalid_argument);
  options = {};
  options.min_turn_rate_radps = 10.0;
  EXPECT_THROW(TravelBehaviour(TravelPlan{}, options), std::invalid_argument);
  TravelPlan plan = makeTravelPlan({{0.0, 0.0}, {1.0, 0.0}}, 0.0);
  plan.segments[0].to.x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(TravelBehaviour{plan}, std::invalid_argument);
  EXPECT_FALSE(travelOptionsError(TravelOptions{}).has_value());
}

TEST(TravelBehaviour, StopsWhenAForwardSonarSeesAnObstacleTheMapDidNotHave) {
  WorldMap map = squareRoom(2.0, {-1.5, 0.0, 0.0});
  Obstacle box;
  box.id = "box";
  box.polygon = {Vec2(0.0, -0.3), Vec2(0.4, -0.3), Vec2(0.4, 0.3), Vec2(0.0, 0.3)};
  map.obstacles.push_back(box);
  Simulator sim = makeSim(map);
  // The irgs-sim form: profile, plan, TravelConfig (forward-sonar stop at 0.25 m).
  TravelBehaviour behaviour(sim.profile(), makeTravelPlan({{-1.5, 0.0}, {1.5, 0.0}}, 0.0));
  run(sim, behaviour, 60.0);
  EXPECT_TRUE(behaviour.status().failed);
  EXPECT_NE(behaviour.status().message.find("blocked"), std::string::npos)
      << behaviour.status().message;
  EXPECT_EQ(sim.bumpers(), 0u);  // stopped before touching it
  EXPECT_LT(sim.truePose().x, -0.1);
}

TEST(TravelBehaviour, TheSonarStopIgnoresAWallBeyondTheTurningPoint) {
  const WorldMap map = squareRoom(1.0, {-0.5, 0.0, 0.0});
  Simulator sim = makeSim(map);
  // The leg ends 0.2 m before the wall, closer than the stop distance: not a blockage.
  TravelBehaviour behaviour(sim.profile(), makeTravelPlan({{-0.5, 0.0}, {0.8, 0.0}}, 0.0),
                            TravelConfig{});
  run(sim, behaviour, 60.0);
  EXPECT_FALSE(behaviour.status().failed) << behaviour.status().message;
  EXPECT_LT((sim.truePose().position() - Vec2(0.8, 0.0)).norm(), 0.03);
  EXPECT_EQ(behaviour.segmentsDone(), 1u);
  EXPECT_THROW(TravelBehaviour(sim.profile(), TravelPlan{}, TravelConfig{-1.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace irgs
