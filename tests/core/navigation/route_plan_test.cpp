#include "core/navigation/route_plan.hpp"

#include <gtest/gtest.h>

#include "core/world/map_file.hpp"

namespace irgs {
namespace {

WorldMap deliveryFloor() {
  const MapLoadResult r =
      loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/delivery_floor_002.json");
  if (!r.map)
    throw std::runtime_error("delivery floor does not load");
  return *r.map;
}

std::vector<std::string> ids(const RoutePlan& plan) {
  std::vector<std::string> out;
  for (const RouteStep& s : plan.steps)
    out.push_back(s.node_id);
  return out;
}

std::vector<MarkerAction> actions(const RoutePlan& plan) {
  std::vector<MarkerAction> out;
  for (const RouteStep& s : plan.steps)
    out.push_back(s.action);
  return out;
}

TopoGraph line(bool bidirectional) {
  TopoGraph g;
  g.nodes = {{"a", {0, 0}, "", {}}, {"b", {2, 0}, "", {}}, {"c", {2, 3}, "", {}}};
  g.edges = {{"a", "b", bidirectional, {}}, {"b", "c", bidirectional, {}}};
  return g;
}

TEST(RoutePlan, DeliveryFromNodeZeroToSixTurnsLeftTwiceThroughTheTJunctions) {
  const RoutePlan plan = planRoute(deliveryFloor().graph, "0", "6");
  ASSERT_EQ(plan.status, RouteStatus::kOk);
  EXPECT_EQ(ids(plan), (std::vector<std::string>{"0", "1", "5", "4", "6"}));
  using A = MarkerAction;
  EXPECT_EQ(actions(plan),
            (std::vector<A>{A::kStraight, A::kLeft, A::kStraight, A::kLeft, A::kStop}));
  EXPECT_NEAR(plan.length_m, 6.5 + 4.25 + 4.25 + 6.0, 1e-9);
  EXPECT_NEAR(plan.steps[1].turn_rad, kPi / 2, 1e-9);
}

TEST(RoutePlan, TheWayBackTurnsRight) {
  const RoutePlan plan = planRoute(deliveryFloor().graph, "6", "0");
  ASSERT_EQ(plan.status, RouteStatus::kOk);
  using A = MarkerAction;
  EXPECT_EQ(actions(plan),
            (std::vector<A>{A::kStraight, A::kRight, A::kStraight, A::kRight, A::kStop}));
}

TEST(RoutePlan, PicksTheShorterWayRoundTheLoop) {
  // 5 -> 2: via 1 is 4.25 + 10 = 14.25 m, via 4 and 3 is 4.25 + 10 + 8.5 = 22.75 m.
  const RoutePlan plan = planRoute(deliveryFloor().graph, "5", "2");
  ASSERT_EQ(plan.status, RouteStatus::kOk);
  EXPECT_EQ(ids(plan), (std::vector<std::string>{"5", "1", "2"}));
  EXPECT_EQ(plan.steps[1].action, MarkerAction::kLeft);  // heading south, turning east
}

TEST(RoutePlan, ReportsUnknownNodesAndMissingPaths) {
  const TopoGraph g = line(false);
  EXPECT_EQ(planRoute(g, "x", "a").status, RouteStatus::kUnknownStart);
  EXPECT_EQ(planRoute(g, "a", "x").status, RouteStatus::kUnknownGoal);
  EXPECT_EQ(planRoute(g, "a", "c").status, RouteStatus::kOk);
  EXPECT_EQ(planRoute(g, "c", "a").status, RouteStatus::kNoPath);  // one-way edges
  EXPECT_EQ(planRoute(line(true), "c", "a").status, RouteStatus::kOk);
}

TEST(RoutePlan, StartEqualToGoalIsAStop) {
  const RoutePlan plan = planRoute(line(true), "b", "b");
  ASSERT_EQ(plan.steps.size(), 1u);
  EXPECT_EQ(plan.steps[0].action, MarkerAction::kStop);
}

TEST(RoutePlan, NodesResolveByIdOrIndex) {
  const TopoGraph g = line(true);
  EXPECT_EQ(resolveNodeId(g, "b"), "b");
  EXPECT_EQ(resolveNodeId(g, "2"), "c");
  EXPECT_EQ(resolveNodeId(g, "3"), "");
  EXPECT_EQ(resolveNodeId(g, "z"), "");
}

}  // namespace
}  // namespace irgs
