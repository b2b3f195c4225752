#include "core/mission/map_building_mission.hpp"

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
  MapBuildingMission behaviour(robot, config);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = robot;
  spec.sim = sim;
  spec.max_duration_s = budget_s;
  BuildRun run;
  run.result = runMissionScenario(spec, behaviour);
  run.score = scoreMap(behaviour.grid(), map, map.start);
  EXPECT_EQ(behaviour.phase(),
            run.result.behaviour.failed ? MapBuildingPhase::kFailed : MapBuildingPhase::kDone);
  return run;
}

TEST(MapBuildingMission, BuildsTheThesisLoopClockwiseWithF1AboveNinety) {
  const WorldMap map = test::loadBundledMap("thesis_sim1_loop");
  const RobotProfile robot = test::thesisRobot();
  MapBuildingMission behaviour(robot);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = robot;
  spec.sim = idealSimConfig();
  spec.max_duration_s = 900.0;
  const auto result = runMissionScenario(spec, behaviour);
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

TEST(MapBuildingMission, CircumnavigatesTheFourObstaclesOfTheSecondThesisMap) {
  const BuildRun run = build("thesis_sim2_four_obstacles", idealSimConfig());
  EXPECT_FALSE(run.result.behaviour.failed) << run.result.behaviour.message;
  EXPECT_GE(run.score.f1, 0.9) << "P " << run.score.precision << " R " << run.score.recall;
  int obstacle_phases = 0;
  for (const auto& p : run.result.behaviour.phases)
    obstacle_phases += p.phase.rfind("obstacle", 0) == 0 ? 1 : 0;
  EXPECT_GE(obstacle_phases, 4);
}

TEST(MapBuildingMission, RecognisesThatTheFirstWallOfTheThirdThesisMapIsAnObstacle) {
  // The start faces the box: the first loop closes counter-clockwise around it (Figs. 5.7.1-3).
  const WorldMap map = test::loadBundledMap("thesis_sim3_five_obstacles");
  const RobotProfile robot = test::thesisRobot();
  MapBuildingMission behaviour(robot);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = robot;
  spec.sim = idealSimConfig();
  spec.max_duration_s = 1500.0;
  const auto result = runMissionScenario(spec, behaviour);
  EXPECT_FALSE(result.behaviour.failed) << result.behaviour.message;
  EXPECT_TRUE(behaviour.firstWallWasObstacle());
  ASSERT_GE(behaviour.obstacleCount(), 5);
  EXPECT_GT(behaviour.obstacleLoops().front().signed_area_m2, 0.0);
  ASSERT_TRUE(behaviour.outline().has_value());
  EXPECT_LT(behaviour.outline()->signed_area_m2, 0.0);
  const MapScore score = scoreMap(behaviour.grid(), map, map.start);
  EXPECT_GE(score.f1, 0.9) << "P " << score.precision << " R " << score.recall;
}

TEST(MapBuildingMission, BuildsTheArenaWithDefaultNoiseAboveEighty) {
  const BuildRun run = build("thesis_arena_250", typicalSimConfig(), {}, 900.0);
  EXPECT_FALSE(run.result.behaviour.failed) << run.result.behaviour.message;
  EXPECT_GE(run.score.f1, 0.8) << "P " << run.score.precision << " R " << run.score.recall;
  EXPECT_EQ(run.result.scenario.metrics.bumper_events, 0u);
}

TEST(MapBuildingMission, APioneerP3dxWhoseCornerCatchesInATurnStillBuildsTheArena) {
  // The P3-DX's rectangular body catches a wall when it turns on the spot in a corner, where no
  // bumper faces the wall: only its drive's stall report tells the wall follower to back out
  // (before, it commanded the turn for ever: 0.85 m in an hour).
  const RobotProfileResult loaded = loadRobotProfileFile(std::filesystem::path(IRGS_SOURCE_DIR) /
                                                         "resources/robots/pioneer_p3dx.json");
  ASSERT_TRUE(loaded.ok());
  const WorldMap map = test::loadBundledMap("thesis_arena_250");
  MapBuildingMission mission(*loaded.profile, {});
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = *loaded.profile;
  spec.sim = typicalSimConfig();
  spec.max_duration_s = 600.0;
  const BehaviourScenarioResult result = runMissionScenario(spec, mission);
  EXPECT_FALSE(result.behaviour.failed) << result.behaviour.message;
  const MapScore score = scoreMap(mission.grid(), map, map.start);
  EXPECT_GE(score.f1, 0.9) << "P " << score.precision << " R " << score.recall;
}

TEST(MapBuildingMission, BuildsTheFourObstacleMapWithDefaultNoiseAboveNinetyOnSeedsOneToFive) {
  // Issue 4: one heading revision on a wrong line used to rotate everything after it (seeds
  // 1-4 gave F1 0.70, 0.82, 0.47, 0.39). The gated revisions and the learned odometry error
  // keep the revised heading within a few degrees of the truth on every seed.
  const WorldMap map = test::loadBundledMap("thesis_sim2_four_obstacles");
  const RobotProfile robot = test::thesisRobot();
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    MapBuildingMission behaviour(robot);
    BehaviourScenarioSpec spec;
    spec.map = map;
    spec.profile = robot;
    spec.sim = typicalSimConfig();
    spec.sim.seed = seed;
    spec.max_duration_s = 1500.0;
    const auto result = runMissionScenario(spec, behaviour);
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
    EXPECT_LT(behaviour.revisedPose().learnedTurnScaleError(), -0.001) << "seed " << seed;
    EXPECT_GT(behaviour.revisedPose().learnedTurnScaleError(), -0.01) << "seed " << seed;
  }
}

TEST(MapBuildingMission, WithoutHeadingRevisionTheNoisyMapIsWorse) {
  // The revisions are what carries the map: switched off, the same run drifts.
  MapBuildingConfig off;
  off.heading_lattice_rad = 0.0;
  const BuildRun with = build("thesis_sim2_four_obstacles", typicalSimConfig());
  const BuildRun without = build("thesis_sim2_four_obstacles", typicalSimConfig(), off);
  EXPECT_GT(with.score.f1, without.score.f1 + 0.05)
      << "with " << with.score.f1 << " without " << without.score.f1;
}

TEST(MapBuildingMission, ABudgetTooSmallEndsAsFailedWithTheReason) {
  MapBuildingConfig config;
  config.max_time_s = 30.0;
  const BuildRun run = build("thesis_sim1_loop", idealSimConfig(), config, 100.0);
  EXPECT_TRUE(run.result.behaviour.finished);
  EXPECT_TRUE(run.result.behaviour.failed);
  EXPECT_NE(run.result.behaviour.message.find("time budget"), std::string::npos);
}

TEST(MapBuildingMission, RejectsAnInvalidConfig) {
  MapBuildingConfig config;
  config.index_spacing_m = 0.0;
  EXPECT_THROW(MapBuildingMission(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.closure_radius_m = 5.0;
  EXPECT_THROW(MapBuildingMission(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.heading_gate_per_m = -0.1;
  EXPECT_THROW(MapBuildingMission(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.position_gate_m = 0.0;
  EXPECT_THROW(MapBuildingMission(test::thesisRobot(), config), std::invalid_argument);
}

TEST(MapBuildingMission, RejectsInvalidRevisionAndExplorationSettings) {
  MapBuildingConfig config;
  config.heading_walk_rad2_per_m = -1.0;
  EXPECT_THROW(MapBuildingMission(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.heading_fit_floor_rad = 0.0;
  EXPECT_THROW(MapBuildingMission(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.wall_ranging_gain = 1.5;
  EXPECT_THROW(MapBuildingMission(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.explore_range_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(MapBuildingMission(test::thesisRobot(), config), std::invalid_argument);
  config = {};
  config.max_obstacle_loop_m = 1.0;  // not longer than min_loop_length_m
  EXPECT_THROW(MapBuildingMission(test::thesisRobot(), config), std::invalid_argument);
}

TEST(MapBuildingMission, LearnsNoOdometryErrorWhenThereIsNone) {
  // The learned model is fitted to the cumulative heading error, so the fit noise of single
  // lines (~0.2 deg) cannot turn into a drift rate that rotates long interior legs (issue 4:
  // on the depot a spurious -0.02 deg/m turned the ideal run by 2 deg between walls).
  const WorldMap map = test::loadBundledMap("thesis_sim2_four_obstacles");
  MapBuildingMission behaviour(test::thesisRobot());
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = test::thesisRobot();
  spec.sim = idealSimConfig();
  spec.max_duration_s = 1500.0;
  const auto result = runMissionScenario(spec, behaviour);
  EXPECT_FALSE(result.behaviour.failed) << result.behaviour.message;
  EXPECT_GT(behaviour.revisedPose().headingCorrections(), 10);
  EXPECT_LT(std::abs(behaviour.revisedPose().learnedDrift_radpm()), degToRad(0.02));
  EXPECT_LT(std::abs(behaviour.revisedPose().learnedTurnScaleError()), 0.001);
  // Without odometry error the final heading is off only by the fit noise of the last
  // obstacle faces: single revisions there measured up to 0.58 deg on this map with either
  // implementation (the old behaviour ended at 0.04 deg, this mission at 0.52 deg, both
  // within that noise), so the bound is one degree, not a lucky half.
  const double heading_error =
      wrapAngle(behaviour.pose().theta - result.scenario.metrics.final_truth.theta);
  EXPECT_LT(std::abs(heading_error), degToRad(1.0));
}

// Final distance between the pose the behaviour worked in and the true pose.
double finalPositionError(bool wall_ranging, std::uint64_t seed, int* range_corrections) {
  const WorldMap map = test::loadBundledMap("thesis_sim2_four_obstacles");
  MapBuildingConfig config;
  config.wall_ranging = wall_ranging;
  MapBuildingMission behaviour(test::thesisRobot(), config);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = test::thesisRobot();
  spec.sim = typicalSimConfig();
  spec.sim.seed = seed;
  spec.max_duration_s = 1500.0;
  const auto result = runMissionScenario(spec, behaviour);
  EXPECT_FALSE(result.behaviour.failed) << result.behaviour.message;
  *range_corrections = behaviour.revisedPose().rangeCorrections();
  return (behaviour.pose().position() - result.scenario.metrics.final_truth.position()).norm();
}

// Ranging is active and the pose stays on the outline. Whether it beats no ranging is not
// settled on this map: over seeds 1-8 the final error is 2.9 cm with and 2.3 cm without
// (seed 1: 2.8 / 2.4 cm), so no single-seed comparison is asserted (docs/map-building.md).
TEST(MapBuildingMission, RangingToRoomWallsKeepsTheNoisyPoseOnTheOutline) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    int with_count = 0, without_count = 0;
    const double with = finalPositionError(true, seed, &with_count);
    const double without = finalPositionError(false, seed, &without_count);
    EXPECT_GT(with_count, 100) << "seed " << seed;
    EXPECT_EQ(without_count, 0) << "seed " << seed;
    EXPECT_LT(with, 0.05) << "seed " << seed;
    EXPECT_LT(without, 0.05) << "seed " << seed;
  }
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

struct DepotRun {
  bool done = false;
  std::string message;
  MapScore score;
  int obstacles = 0;
};

DepotRun buildDepot(const WorldMap& map, bool noisy, std::uint64_t seed) {
  MapBuildingConfig config;
  config.max_time_s = 7200.0;
  MapBuildingMission behaviour(test::thesisRobot(), config);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = test::thesisRobot();
  spec.sim = noisy ? typicalSimConfig() : idealSimConfig();
  spec.sim.seed = seed;
  spec.max_duration_s = 7200.0;
  const auto result = runMissionScenario(spec, behaviour);
  return {behaviour.phase() == MapBuildingPhase::kDone, result.behaviour.message,
          scoreMap(behaviour.grid(), map, map.start), behaviour.obstacleCount()};
}

TEST(MapBuildingMission, BuildsTheDepotWithinTwoHoursIdealAndOnThreeNoisySeeds) {
  const auto map = depotMap();
  if (!map)
    GTEST_SKIP() << "../shared/maps/ros/depot.yaml not present";
  const DepotRun ideal = buildDepot(*map, false, 1);
  EXPECT_TRUE(ideal.done) << ideal.message;
  EXPECT_GE(ideal.score.f1, 0.9) << "P " << ideal.score.precision << " R " << ideal.score.recall;
  EXPECT_GT(ideal.obstacles, 15);
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const DepotRun noisy = buildDepot(*map, true, seed);
    EXPECT_TRUE(noisy.done) << "seed " << seed << ": " << noisy.message;
    EXPECT_GT(noisy.obstacles, 15) << "seed " << seed;
  }
}

// Issue 4's target with the default noise, not met by the mission on primitives today: seeds
// 1-3 give F1 0.819, 0.810, 0.702 (the former host loop 0.890, 0.798, 0.903). Kept as the
// claim to meet (issue 25: localization while mapping); run it with
// --gtest_also_run_disabled_tests.
TEST(MapBuildingMission, DISABLED_BuildsTheDepotWithDefaultNoiseAtF1AboveEighty) {
  const auto map = depotMap();
  if (!map)
    GTEST_SKIP() << "../shared/maps/ros/depot.yaml not present";
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const DepotRun noisy = buildDepot(*map, true, seed);
    EXPECT_GE(noisy.score.f1, 0.8)
        << "seed " << seed << " P " << noisy.score.precision << " R " << noisy.score.recall;
  }
}

TEST(MapBuildingMission, SameSeedGivesTheSameGrid) {
  MapBuildingConfig config;
  const BuildRun a = build("thesis_arena_250", typicalSimConfig(), config, 300.0);
  const WorldMap map = test::loadBundledMap("thesis_arena_250");
  MapBuildingMission b(test::thesisRobot(), config);
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = test::thesisRobot();
  spec.sim = typicalSimConfig();
  spec.max_duration_s = 300.0;
  const auto r = runMissionScenario(spec, b);
  EXPECT_EQ(r.scenario.metrics.steps, a.result.scenario.metrics.steps);
  EXPECT_DOUBLE_EQ(r.scenario.metrics.final_truth.x, a.result.scenario.metrics.final_truth.x);
  EXPECT_DOUBLE_EQ(scoreMap(b.grid(), map, map.start).f1, a.score.f1);
}

}  // namespace
}  // namespace irgs
