#include "core/navigation/landmark_navigator.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "core/navigation/ideal_ceiling_observer.hpp"
#include "core/sim/diff_drive.hpp"

namespace irgs {
namespace {

// Three markers on an L: a (0,0) -> b (6,0) -> c (6,5); lights along both legs.
WorldMap lFloor() {
  WorldMap map;
  map.ceiling_height_m = 2.6;
  const std::vector<std::pair<std::string, Vec2>> nodes = {
      {"a", {0.0, 0.0}}, {"b", {6.0, 0.0}}, {"c", {6.0, 5.0}}};
  for (const auto& [id, p] : nodes) {
    map.markers.push_back({"M" + id, p, 0.0, 0.2, {}});
    map.graph.nodes.push_back({id, p, "M" + id, {}});
  }
  map.graph.edges = {{"a", "b", true, {}}, {"b", "c", true, {}}};
  for (double x : {1.5, 3.0, 4.5})
    map.lights.push_back({"", Segment{Vec2(x - 0.5, 0.0), Vec2(x + 0.5, 0.0)}, 0.1, {}});
  for (double y : {1.5, 3.0})
    map.lights.push_back({"", Segment{Vec2(6.0, y - 0.5), Vec2(6.0, y + 0.5)}, 0.1, {}});
  return map;
}

struct Trace {
  std::vector<NavState> states;
  Pose2 final_pose;
  double max_speed_near_marker = 0.0;  // within 0.5 m of b
  double max_tilt_near_marker = 0.0;
  double time_s = 0.0;
};

// Perfect kinematics (pose = odometry = truth), no obstacles, 100 Hz control, 10 Hz camera.
Trace drive(const WorldMap& map, Pose2 pose) {
  IdealCeilingObserver camera(map, IdealCameraParams{}, 3);
  LandmarkNavigator nav(planRoute(map.graph, "a", "c"), LandmarkNavigatorParams{});
  const std::vector<SonarRay> sonar = {{Vec2::UnitX(), 4.0}};
  Trace trace;
  CeilingObservation obs;
  double tilt = nav.params().tilt.min_tilt_rad;
  for (int k = 0; k < 6000 && !nav.arrived(); ++k) {
    const double t = 0.01 * k;
    NavigatorInput in;
    in.time_s = t;
    in.odometry = pose;
    in.sonar = sonar;
    if (k % 10 == 0) {
      obs = camera.observe(pose, tilt, t);
      in.observation = &obs;
    }
    const NavigatorOutput out = nav.update(in);
    tilt = out.tilt_rad;
    if (trace.states.empty() || trace.states.back() != nav.state())
      trace.states.push_back(nav.state());
    if ((pose.position() - Vec2(6.0, 0.0)).norm() < 0.5 && nav.nextStep() == 1) {
      trace.max_speed_near_marker = std::max(trace.max_speed_near_marker, out.command.linear_mps);
      trace.max_tilt_near_marker = std::max(trace.max_tilt_near_marker, out.tilt_rad);
    }
    pose = integrateArc(pose, out.command.linear_mps * 0.01, out.command.angular_radps * 0.01);
    trace.time_s = t;
  }
  trace.final_pose = pose;
  return trace;
}

TEST(LandmarkNavigator, FollowsLightsThenTheMarkerTurnsAtTheCornerAndStopsUnderTheGoal) {
  const Trace trace = drive(lFloor(), {0.0, 0.0, 0.0});
  ASSERT_FALSE(trace.states.empty());
  EXPECT_EQ(trace.states.back(), NavState::kArrived);
  EXPECT_LT((trace.final_pose.position() - Vec2(6.0, 5.0)).norm(), 0.12);
  const auto has = [&](NavState s) {
    return std::find(trace.states.begin(), trace.states.end(), s) != trace.states.end();
  };
  EXPECT_TRUE(has(NavState::kFollowLight));
  EXPECT_TRUE(has(NavState::kFollowMarker));
  EXPECT_TRUE(has(NavState::kTurnAtMarker));
  // Fig. 20: near the marker the camera looks up and the robot creeps.
  EXPECT_GT(trace.max_tilt_near_marker, degToRad(70.0));
  EXPECT_LT(trace.max_speed_near_marker, 0.3);
  EXPECT_LT(trace.time_s, 60.0);
}

TEST(LandmarkNavigator, StartingOffTheHeadingTurnsOntoTheFirstEdgeFirst) {
  const Trace trace = drive(lFloor(), {0.0, 0.0, kPi / 2});
  ASSERT_GE(trace.states.size(), 2u);
  EXPECT_EQ(trace.states.front(), NavState::kDepart);
  EXPECT_EQ(trace.states.back(), NavState::kArrived);
}

TEST(LandmarkNavigator, WithNothingInViewItGoesStraightAhead) {
  WorldMap map = lFloor();
  map.markers.clear();
  map.lights.clear();
  IdealCeilingObserver camera(map, IdealCameraParams{}, 3);
  LandmarkNavigator nav(planRoute(map.graph, "a", "c"), LandmarkNavigatorParams{});
  CeilingObservation obs = camera.observe({}, degToRad(35.0), 0.0);
  NavigatorInput in;
  in.observation = &obs;
  const NavigatorOutput out = nav.update(in);
  EXPECT_EQ(nav.state(), NavState::kStraight);
  EXPECT_GT(out.command.linear_mps, 0.0);
  EXPECT_NEAR(out.command.angular_radps, 0.0, 1e-12);
}

TEST(LandmarkNavigator, AnObstacleAheadLeftSteersRightAndSlowsDown) {
  const WorldMap map = lFloor();
  LandmarkNavigator nav(planRoute(map.graph, "a", "c"), LandmarkNavigatorParams{});
  CeilingObservation none;
  const std::vector<SonarRay> sonar = {{Vec2(std::cos(0.2), std::sin(0.2)), 0.5},
                                       {Vec2(std::cos(-0.6), std::sin(-0.6)), 4.0}};
  NavigatorInput in;
  in.observation = &none;
  in.sonar = sonar;
  const NavigatorOutput out = nav.update(in);
  EXPECT_LT(out.repulsive_body.y(), 0.0);
  EXPECT_LT(out.command.angular_radps, 0.0);
  EXPECT_LT(out.command.linear_mps, LandmarkNavigatorParams{}.cruise_speed_mps * 0.5);
  EXPECT_NEAR((out.move_body - (out.target_body + out.repulsive_body)).norm(), 0.0, 1e-12);
}

TEST(LandmarkNavigator, RefusesARouteThatWasNotPlanned) {
  EXPECT_THROW(LandmarkNavigator(RoutePlan{}, LandmarkNavigatorParams{}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
