#include "core/behaviour/map_building.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>

#include "core/mapping/map_score.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/scenario/behaviour_runner.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/world/map_file.hpp"
#include "tests/core/behaviour/behaviour_test_support.hpp"
#include "tests/core/behaviour/sampled_link.hpp"

namespace irgs {
namespace {

struct BuildRun {
  BehaviourScenarioResult result;
  MapScore score;
};

BuildRun build(const std::string& map_name, SimConfig sim, MapBuildingConfig config = {},
               double budget_s = 1500.0) {
  const WorldMap map = test::loadBundledMap(map_name);
  const RobotProfile robot = test::thesisRobot();
  MapBuildingBehaviour behaviour(robot, config);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = robot;
  spec.sim = sim;
  spec.max_duration_s = budget_s;
  BuildRun run;
  run.result = runBehaviourScenario(spec, behaviour);
  run.score = scoreMap(behaviour.grid(), map, map.start);
  EXPECT_EQ(behaviour.phase(),
            run.result.behaviour.failed ? MapBuildingPhase::kFailed : MapBuildingPhase::kDone);
  return run;
}

// The AmigoBot of the ARCOS e2e test.
RobotProfile amigoBot() {
  auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/pioneer_amigo.json");
  if (!loaded.profile)
    throw std::runtime_error("resources/robots/pioneer_amigo.json does not load");
  return *loaded.profile;
}

// A loaded ground station's link (sampled_link.hpp): answers up to 0.3 s later than the 0.1 s
// delay, and a 5 % chance per answer of a 0.2-1 s freeze.
test::SampledLink loadedStationLink(unsigned seed) {
  test::SampledLink link;
  link.jitter_s = 0.3;
  link.freeze_probability = 0.05;
  link.seed = seed;
  return link;
}

TEST(MapBuilding, BuildsTheThesisLoopClockwiseWithF1AboveNinety) {
  const WorldMap map = test::loadBundledMap("thesis_sim1_loop");
  const RobotProfile robot = test::thesisRobot();
  MapBuildingBehaviour behaviour(robot);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = robot;
  spec.sim = idealSimConfig();
  spec.max_duration_s = 900.0;
  const auto result = runBehaviourScenario(spec, behaviour);
  ASSERT_TRUE(result.behaviour.finished);
  EXPECT_FALSE(result.behaviour.failed) << result.behaviour.message;
  ASSERT_TRUE(behaviour.outline().has_value());
  EXPECT_LT(behaviour.outline()->signed_area_m2, 0.0);  // walls traced clockwise
  EXPECT_FALSE(behaviour.firstWallWasObstacle());
  EXPECT_EQ(behaviour.obstacleCount(), 0);
  EXPECT_GT(behaviour.allIndices().size(), 20u);
  // Phases in the thesis order.
  std::vector<std::string> phases;
  for (const auto& p : result.behaviour.phases)
    phases.push_back(p.phase);
  ASSERT_GE(phases.size(), 4u);
  EXPECT_EQ(phases[0], "scan");
  EXPECT_EQ(phases[1], "seek wall");
  EXPECT_EQ(phases[2], "follow wall");
  EXPECT_EQ(phases[3], "loop closed");
  EXPECT_EQ(phases.back(), "done");
  const MapScore score = scoreMap(behaviour.grid(), map, map.start);
  EXPECT_GE(score.f1, 0.9) << "P " << score.precision << " R " << score.recall;
  EXPECT_EQ(result.scenario.metrics.bumper_events, 0u);
}

TEST(MapBuilding, CircumnavigatesTheFourObstaclesOfTheSecondThesisMap) {
  const BuildRun run = build("thesis_sim2_four_obstacles", idealSimConfig());
  EXPECT_FALSE(run.result.behaviour.failed) << run.result.behaviour.message;
  EXPECT_GE(run.score.f1, 0.9) << "P " << run.score.precision << " R " << run.score.recall;
  int obstacle_phases = 0;
  for (const auto& p : run.result.behaviour.phases)
    obstacle_phases += p.phase.rfind("obstacle", 0) == 0 ? 1 : 0;
  EXPECT_GE(obstacle_phases, 4);
}

TEST(MapBuilding, RecognisesThatTheFirstWallOfTheThirdThesisMapIsAnObstacle) {
  // The start faces the box: the first loop closes counter-clockwise around it (Figs. 5.7.1-3).
  const WorldMap map = test::loadBundledMap("thesis_sim3_five_obstacles");
  const RobotProfile robot = test::thesisRobot();
  MapBuildingBehaviour behaviour(robot);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = robot;
  spec.sim = idealSimConfig();
  spec.max_duration_s = 1500.0;
  const auto result = runBehaviourScenario(spec, behaviour);
  EXPECT_FALSE(result.behaviour.failed) << result.behaviour.message;
  EXPECT_TRUE(behaviour.firstWallWasObstacle());
  ASSERT_GE(behaviour.obstacleCount(), 5);
  EXPECT_GT(behaviour.obstacleLoops().front().signed_area_m2, 0.0);
  ASSERT_TRUE(behaviour.outline().has_value());
  EXPECT_LT(behaviour.outline()->signed_area_m2, 0.0);
  const MapScore score = scoreMap(behaviour.grid(), map, map.start);
  EXPECT_GE(score.f1, 0.9) << "P " << score.precision << " R " << score.recall;
}

TEST(MapBuilding, BuildsTheArenaWithDefaultNoiseAboveEighty) {
  const BuildRun run = build("thesis_arena_250", typicalSimConfig(), {}, 900.0);
  EXPECT_FALSE(run.result.behaviour.failed) << run.result.behaviour.message;
  EXPECT_GE(run.score.f1, 0.8) << "P " << run.score.precision << " R " << run.score.recall;
  EXPECT_EQ(run.result.scenario.metrics.bumper_events, 0u);
}

TEST(MapBuilding, BuildsTheFourObstacleMapWithDefaultNoiseAboveNinetyOnSeedsOneToFive) {
  // Issue 4: one heading revision on a wrong line used to rotate everything after it (seeds
  // 1-4 gave F1 0.70, 0.82, 0.47, 0.39). The gated revisions and the learned odometry error
  // keep the revised heading within a few degrees of the truth on every seed.
  const WorldMap map = test::loadBundledMap("thesis_sim2_four_obstacles");
  const RobotProfile robot = test::thesisRobot();
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    MapBuildingBehaviour behaviour(robot);
    BehaviourScenarioSpec spec;
    spec.map = map;
    spec.profile = robot;
    spec.sim = typicalSimConfig();
    spec.sim.seed = seed;
    spec.max_duration_s = 1500.0;
    const auto result = runBehaviourScenario(spec, behaviour);
    EXPECT_FALSE(result.behaviour.failed) << "seed " << seed << ": " << result.behaviour.message;
    EXPECT_EQ(behaviour.obstacleCount(), 4) << "seed " << seed;
    const MapScore score = scoreMap(behaviour.grid(), map, map.start);
    EXPECT_GE(score.f1, 0.9) << "seed " << seed << " P " << score.precision << " R "
                             << score.recall;
    const double heading_error =
        wrapAngle(behaviour.pose().theta - result.scenario.metrics.final_truth.theta);
    EXPECT_LT(std::abs(heading_error), degToRad(3.0)) << "seed " << seed;
    // The simulated wheelbase is 0.5 % wider than the odometry's: odometry over-counts every
    // turn, which the revisions learn as a negative error per radian turned.
    EXPECT_LT(behaviour.learnedTurnScaleError(), -0.001) << "seed " << seed;
    EXPECT_GT(behaviour.learnedTurnScaleError(), -0.01) << "seed " << seed;
  }
}

TEST(MapBuilding, WithoutHeadingRevisionTheNoisyMapIsWorse) {
  // The revisions are what carries the map: switched off, the same run drifts.
  MapBuildingConfig off;
  off.heading_lattice_rad = 0.0;
  const BuildRun with = build("thesis_sim2_four_obstacles", typicalSimConfig());
  const BuildRun without = build("thesis_sim2_four_obstacles", typicalSimConfig(), off);
  EXPECT_GT(with.score.f1, without.score.f1 + 0.05)
      << "with " << with.score.f1 << " without " << without.score.f1;
}

TEST(MapBuilding, ABudgetTooSmallEndsAsFailedWithTheReason) {
  MapBuildingConfig config;
  config.max_time_s = 30.0;
  const BuildRun run = build("thesis_sim1_loop", idealSimConfig(), config, 100.0);
  EXPECT_TRUE(run.result.behaviour.finished);
  EXPECT_TRUE(run.result.behaviour.failed);
  EXPECT_NE(run.result.behaviour.message.find("time budget"), std::string::npos);
}

TEST(MapBuilding, RejectsAnInvalidConfig) {
  MapBuildingConfig config;
  config.index_spacing_m = 0.0;
  EXPECT_THROW(MapBuildingBehaviour(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.closure_radius_m = 5.0;
  EXPECT_THROW(MapBuildingBehaviour(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.heading_gate_per_m = -0.1;
  EXPECT_THROW(MapBuildingBehaviour(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.position_gate_m = 0.0;
  EXPECT_THROW(MapBuildingBehaviour(test::thesisRobot(), config), std::invalid_argument);
}

TEST(MapBuilding, RejectsInvalidRevisionAndExplorationSettings) {
  MapBuildingConfig config;
  config.heading_walk_rad2_per_m = -1.0;
  EXPECT_THROW(MapBuildingBehaviour(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.heading_fit_floor_rad = 0.0;
  EXPECT_THROW(MapBuildingBehaviour(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.wall_ranging_gain = 1.5;
  EXPECT_THROW(MapBuildingBehaviour(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.explore_range_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(MapBuildingBehaviour(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.max_obstacle_loop_m = 1.0;  // not longer than min_loop_length_m
  EXPECT_THROW(MapBuildingBehaviour(test::thesisRobot(), config), std::invalid_argument);
}

TEST(MapBuilding, LearnsNoOdometryErrorWhenThereIsNone) {
  // The learned model is fitted to the cumulative heading error, so the fit noise of single
  // lines (~0.2 deg) cannot turn into a drift rate that rotates long interior legs (issue 4:
  // on the depot a spurious -0.02 deg/m turned the ideal run by 2 deg between walls).
  const WorldMap map = test::loadBundledMap("thesis_sim2_four_obstacles");
  MapBuildingBehaviour behaviour(test::thesisRobot());
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = test::thesisRobot();
  spec.sim = idealSimConfig();
  spec.max_duration_s = 1500.0;
  const auto result = runBehaviourScenario(spec, behaviour);
  EXPECT_FALSE(result.behaviour.failed) << result.behaviour.message;
  EXPECT_GT(behaviour.headingCorrections(), 10);
  EXPECT_LT(std::abs(behaviour.learnedDrift_radpm()), degToRad(0.02));
  EXPECT_LT(std::abs(behaviour.learnedTurnScaleError()), 0.001);
  const double heading_error =
      wrapAngle(behaviour.pose().theta - result.scenario.metrics.final_truth.theta);
  EXPECT_LT(std::abs(heading_error), degToRad(0.5));
}

// Final distance between the pose the behaviour worked in and the true pose.
double finalPositionError(bool wall_ranging, std::uint64_t seed, int* range_corrections) {
  const WorldMap map = test::loadBundledMap("thesis_sim2_four_obstacles");
  MapBuildingConfig config;
  config.wall_ranging = wall_ranging;
  MapBuildingBehaviour behaviour(test::thesisRobot(), config);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = test::thesisRobot();
  spec.sim = typicalSimConfig();
  spec.sim.seed = seed;
  spec.max_duration_s = 1500.0;
  const auto result = runBehaviourScenario(spec, behaviour);
  EXPECT_FALSE(result.behaviour.failed) << result.behaviour.message;
  *range_corrections = behaviour.rangeCorrections();
  return (behaviour.pose().position() - result.scenario.metrics.final_truth.position()).norm();
}

TEST(MapBuilding, RangingToRoomWallsKeepsTheNoisyPoseOnTheOutline) {
  int with_count = 0, without_count = 0;
  const double with = finalPositionError(true, 1, &with_count);
  const double without = finalPositionError(false, 1, &without_count);
  EXPECT_GT(with_count, 100);
  EXPECT_EQ(without_count, 0);
  EXPECT_LT(with, 0.05);
  EXPECT_LT(with, without);
}

// The depot (../shared/maps/ros, not part of the project: skipped when absent): 30 m x 15 m,
// ten boxes in two rows with a post between them, H-shaped racks, eighteen posts.
std::optional<WorldMap> depotMap() {
  namespace fs = std::filesystem;
  const fs::path p = fs::path(IRGS_SOURCE_DIR) / ".." / "shared" / "maps" / "ros" / "depot.yaml";
  if (!fs::exists(p))
    return std::nullopt;
  return loadAnyMap(p).map;
}

TEST(MapBuilding, BuildsTheDepotWithinTwoHoursIdealAndWithDefaultNoise) {
  const auto map = depotMap();
  if (!map)
    GTEST_SKIP() << "../shared/maps/ros/depot.yaml not present";
  for (const bool noisy : {false, true}) {
    MapBuildingConfig config;
    config.max_time_s = 7200.0;
    MapBuildingBehaviour behaviour(test::thesisRobot(), config);
    BehaviourScenarioSpec spec;
    spec.map = *map;
    spec.profile = test::thesisRobot();
    spec.sim = noisy ? typicalSimConfig() : idealSimConfig();
    spec.max_duration_s = 7200.0;
    const auto result = runBehaviourScenario(spec, behaviour);
    EXPECT_EQ(behaviour.phase(), MapBuildingPhase::kDone)
        << (noisy ? "noise: " : "ideal: ") << result.behaviour.message;
    const MapScore score = scoreMap(behaviour.grid(), *map, map->start);
    EXPECT_GE(score.f1, noisy ? 0.8 : 0.9)
        << (noisy ? "noise" : "ideal") << " P " << score.precision << " R " << score.recall;
    EXPECT_GT(behaviour.obstacleCount(), 15);
  }
}

TEST(MapBuilding, SameSeedGivesTheSameGrid) {
  MapBuildingConfig config;
  const BuildRun a = build("thesis_arena_250", typicalSimConfig(), config, 300.0);
  const WorldMap map = test::loadBundledMap("thesis_arena_250");
  MapBuildingBehaviour b(test::thesisRobot(), config);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = test::thesisRobot();
  spec.sim = typicalSimConfig();
  spec.max_duration_s = 300.0;
  const auto r = runBehaviourScenario(spec, b);
  EXPECT_EQ(r.scenario.metrics.steps, a.result.scenario.metrics.steps);
  EXPECT_DOUBLE_EQ(r.scenario.metrics.final_truth.x, a.result.scenario.metrics.final_truth.x);
  EXPECT_DOUBLE_EQ(scoreMap(b.grid(), map, map.start).f1, a.score.f1);
}

TEST(MapBuilding, BuildsTheArenaOverATenHertzDelayedLinkWithoutHuntingInTheTurns) {
  // The ARCOS e2e test's run (AmigoBot, thesis arena, SIPs at 10 Hz) with the link modelled
  // in-process and 100 ms of command delay: the on-the-spot turns used to hunt across their
  // target heading at turnRate's floor until a sample happened to catch a reversal inside the
  // tolerance (the e2e run took 130-365 s for the same map and once timed out at 500 s).
  const WorldMap map = test::loadBundledMap("thesis_arena_250");
  auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/pioneer_amigo.json");
  ASSERT_TRUE(loaded.profile);
  const RobotProfile robot = *loaded.profile;
  MapBuildingBehaviour behaviour(robot);
  Simulator sim(map, robot, idealSimConfig());
  sim.resetPose(map.start);
  const test::SampledLinkRun run = test::runOverSampledLink(sim, behaviour, {0.1, 0.1}, 600.0);
  ASSERT_TRUE(run.finished) << "still in '" << behaviour.status().phase << "' after " << run.time_s
                            << " s";
  EXPECT_FALSE(run.failed) << behaviour.status().message;
  std::printf("over the link: %.1f s, %d on-the-spot turns, %d reversals, longest %.1f s\n",
              run.time_s, run.spot_turns, run.turn_reversals, run.longest_spot_turn_s);
  EXPECT_LT(run.time_s, 250.0);
  EXPECT_LT(run.longest_spot_turn_s, 15.0);  // the initial scan (7.9 s) and the turn after it
  // At most two overshoots per turn (the AmigoBot brakes at 100 deg/s^2: the proportional
  // approach from 60 deg/s overshoots, then the floor's approach may once more); the old rule
  // never ended the first turn after the scan.
  EXPECT_LE(run.turn_reversals, 2 * run.spot_turns);
  EXPECT_GE(behaviour.obstacleCount(), 1);
  const MapScore score = scoreMap(behaviour.grid(), map, map.start);
  EXPECT_GE(score.f1, 0.9) << "P " << score.precision << " R " << score.recall;
}

TEST(MapBuilding, BuildsTheArenaOverALoadedStationsLinkWithoutWedgingAgainstTheBox) {
  // The ARCOS e2e run on a loaded CI machine: answers late by a varying amount and, now and
  // then, a ground station that stalls for up to a second. Circumnavigating the box, the
  // AmigoBot's rear corner ended up against it: backing up and the 30-degree turn away were both
  // blocked, and the follower alternated between them for 500 s, wheels stalled (seeds 4 and 6
  // here, at the box and at the outline). The escape ladder creeps forward or turns the other
  // way instead.
  const WorldMap map = test::loadBundledMap("thesis_arena_250");
  const RobotProfile robot = amigoBot();
  for (unsigned seed = 0; seed < 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    MapBuildingBehaviour behaviour(robot);
    SimConfig sim_config = seed == 0 ? idealSimConfig() : typicalSimConfig();
    sim_config.seed = seed;
    Simulator sim(map, robot, sim_config);
    sim.resetPose(map.start);
    const test::SampledLinkRun run =
        test::runOverSampledLink(sim, behaviour, loadedStationLink(seed), 600.0);
    EXPECT_TRUE(run.finished) << "still in '" << behaviour.status().phase << "' ("
                              << behaviour.status().message << ") after " << run.time_s << " s";
    EXPECT_FALSE(run.failed) << behaviour.status().message;
    // A stall lasts until the escape ladder finds a free move: a few blocked_s at most.
    EXPECT_LT(run.longest_stall_s, 10.0);
    // Late, uneven answers cost heading accuracy (0.75-0.98 over these seeds, 0.95+ on a quiet
    // link): a floor, not the quality claim.
    const MapScore score = scoreMap(behaviour.grid(), map, map.start);
    EXPECT_GE(score.f1, 0.7) << "P " << score.precision << " R " << score.recall;
    std::printf("seed %u: %.1f s, longest stall %.1f s, %d obstacle(s), F1 %.3f\n", seed,
                run.time_s, run.longest_stall_s, behaviour.obstacleCount(), score.f1);
  }
}

TEST(MapBuilding, AnInteriorPocketWhereOnlyTurningIsFreeDoesNotLivelock) {
  // One run of a 200-seed sweep of that loaded link: exploring the interior, the AmigoBot ended in
  // the pocket between the arena's right wall and the 45-degree cut, where it could turn through
  // 65-113 degrees but not drive. Its planned turn (past 113) blocked, the back-up blocked, the
  // escape turn the other way completed, that reset the ladder and the plan turned it back into
  // the block: for good (3000 s). Only driving 10 cm or a turn of the plan's own now resets it.
  const WorldMap map = test::loadBundledMap("thesis_arena_250");
  const RobotProfile robot = amigoBot();
  MapBuildingBehaviour behaviour(robot);
  SimConfig sim_config = typicalSimConfig();
  sim_config.seed = 166;
  Simulator sim(map, robot, sim_config);
  sim.resetPose(map.start);
  const test::SampledLinkRun run =
      test::runOverSampledLink(sim, behaviour, loadedStationLink(1166), 900.0);
  ASSERT_TRUE(run.finished) << "still in '" << behaviour.status().phase << "' after " << run.time_s
                            << " s";
  EXPECT_FALSE(run.failed) << behaviour.status().message;
  std::printf("%.1f s, longest stall %.1f s\n", run.time_s, run.longest_stall_s);
}

TEST(MapBuilding, TwoHundredLoadedLinkRunsOnTheArenaAllFinishWithoutALongStall) {
  // The sweep behind docs/decisions.md "Blocked moves: the escape ladder": sim seed s with
  // default noise, link seed s + 1000, the loaded-station link of the test above, 900 s each.
  // Before the ladder 14 of these did not finish (stalls up to 827 s).
  const WorldMap map = test::loadBundledMap("thesis_arena_250");
  const RobotProfile robot = amigoBot();
  double longest_stall_s = 0.0, longest_run_s = 0.0, f1_sum = 0.0;
  int below_08 = 0;
  for (unsigned seed = 0; seed < 200; ++seed) {
    MapBuildingBehaviour behaviour(robot);
    SimConfig sim_config = typicalSimConfig();
    sim_config.seed = seed;
    Simulator sim(map, robot, sim_config);
    sim.resetPose(map.start);
    const test::SampledLinkRun run =
        test::runOverSampledLink(sim, behaviour, loadedStationLink(seed + 1000), 900.0);
    EXPECT_TRUE(run.finished && !run.failed)
        << "seed " << seed << ": '" << behaviour.status().phase << "' ("
        << behaviour.status().message << ") after " << run.time_s << " s";
    EXPECT_LT(run.longest_stall_s, 10.0) << "seed " << seed;
    longest_stall_s = std::max(longest_stall_s, run.longest_stall_s);
    longest_run_s = std::max(longest_run_s, run.time_s);
    const double f1 = scoreMap(behaviour.grid(), map, map.start).f1;
    f1_sum += f1;
    below_08 += f1 < 0.8 ? 1 : 0;
  }
  std::printf("200 runs: longest %.1f s, longest stall %.1f s, F1 mean %.3f, %d below 0.8\n",
              longest_run_s, longest_stall_s, f1_sum / 200.0, below_08);
}

}  // namespace
}  // namespace irgs
